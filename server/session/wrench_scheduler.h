#pragma once
// External wrenches requested by clients, kept between steps and applied to
// the world at each step boundary.
//
// Steps are numbered as on the wire: the step taken from a world that has
// taken s steps is step s + 1. A wrench accepted for step k acts during
// steps k, k+1, ... as its mode says:
//  - OneStep: step k only.
//  - Duration: `durationSteps` steps from k.
//  - Persistent: until cleared; a new persistent wrench from the same client
//    on the same body replaces the old one when it starts.
//  - Clear: at step k removes the client's active duration and persistent
//    wrenches on the body (on all bodies when the body name is empty).
//  - ClearAllClients: the same for the wrenches of every client.
// Everything is processed in acceptance order, so the result depends only on
// the sequence of accepted requests: replayable and deterministic.

#include <cstdint>
#include <string>
#include <vector>

#include "rbsim/physics/types.h"
#include "rbsim/physics/world.h"

namespace rbsim {

// The frame of a wrench's vectors or point: the world, or the frame the body
// was given in (its shape frame, as for a URDF link; the wire's FRAME_BODY).
// Not the physics' body frame (Wrench::Frame::Body, centre of mass and
// principal axes): applyForStep takes shape-frame values into it.
enum class WrenchFrame { World, ShapeFrame };
enum class WrenchMode { OneStep, Duration, Persistent, Clear, ClearAllClients };

inline bool isClear(WrenchMode mode) {
  return mode == WrenchMode::Clear || mode == WrenchMode::ClearAllClients;
}

struct WrenchRequest {
  std::string client;
  int64_t seq = 0;
  std::string body;  // empty only for the clears (= every body)
  WrenchFrame frame = WrenchFrame::World;       // of force and torque
  WrenchFrame pointFrame = WrenchFrame::World;  // of point
  Vec3 force = Vec3::Zero();                    // N, in `frame`
  Vec3 torque = Vec3::Zero();                   // N·m, in `frame`
  // m, in `pointFrame`: a world position, or a point of the body's shape
  // frame. A world point is taken into the body when the wrench first acts
  // (the request then holds that shape-frame point and pointFrame = Body),
  // so from then on it moves with the body.
  Vec3 point = Vec3::Zero();
  WrenchMode mode = WrenchMode::OneStep;
  int64_t durationSteps = 1;   // Duration only, >= 1
  int64_t firstStep = 0;       // the step during which it first acts
};

class WrenchScheduler {
 public:
  // The request must already be validated (body exists, finite values,
  // firstStep not in the past).
  void add(const WrenchRequest& request);
  // How many duration and persistent wrenches `clear` (a Clear or
  // ClearAllClients request not yet added) will remove when it starts at its
  // firstStep, if it is added now and nothing else is added or removed
  // before then: the lists are run forward without a world to that step.
  int countClearedBy(const WrenchRequest& clear) const;

  // Applies the wrenches acting during `step` (= world.stepCount() + 1) to the
  // world's bodies: call right before world.step(). Wrenches whose body no
  // longer exists are dropped; world points of wrenches acting for the first
  // time are fixed in their body at its current pose.
  void applyForStep(World& world, int64_t step);
  // Call right after world.step(): retires wrenches that have run out.
  void finishStep(int64_t step);

  void clearAll() {
    m_pending.clear();
    m_active.clear();
  }
  void removeBody(const std::string& body);
  // Replaces both lists (a checkpoint being restored), orders kept.
  void restore(std::vector<WrenchRequest> pending, std::vector<WrenchRequest> active) {
    m_pending = std::move(pending);
    m_active = std::move(active);
  }

  int activeCount() const { return static_cast<int>(m_active.size()); }
  int pendingCount() const { return static_cast<int>(m_pending.size()); }
  const std::vector<WrenchRequest>& active() const { return m_active; }
  const std::vector<WrenchRequest>& pending() const { return m_pending; }

 private:
  // Starts one request; returns how many wrenches a clear removed (else 0).
  int start(const WrenchRequest& request);

  std::vector<WrenchRequest> m_pending;  // firstStep in the future, acceptance order
  std::vector<WrenchRequest> m_active;   // acting now, acceptance order
};

}  // namespace rbsim
