#pragma once
// A rigid body: its immutable description and its moving state. Internal to
// the physics library: users read bodies through BodyView (rbsim/physics/
// body_view.h) and change them through World, which keeps its bookkeeping
// (sleep, the guard, load tracking) consistent with every change.

#include <cstdint>
#include <memory>
#include <string>

#include "rbsim/physics/freeze_reason.h"
#include "rbsim/physics/rigid_state.h"
#include "rbsim/physics/body_view.h"
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

class Body {
 public:
  // `dynamics` must already hold the principal moments of `description`.
  Body(std::shared_ptr<const BodyDescription> description, const BodyDynamics& dynamics,
       const RigidState& state);

  const BodyDescription& description() const { return *m_description; }
  const std::shared_ptr<const BodyDescription>& sharedDescription() const { return m_description; }
  const std::string& name() const { return m_description->name; }
  // Never reused within a world: the n-th body created has serial n (from 1).
  // Creation order is ascending serial order.
  int32_t serial() const { return m_serial; }
  bool isStatic() const { return m_description->isStatic; }

  const BodyDynamics& dynamics() const { return m_dynamics; }
  double mass() const { return m_dynamics.mass; }               // kg (0 for static)
  double inverseMass() const { return m_dynamics.inverseMass; }  // 1/kg

  const RigidState& state() const { return m_state; }
  const Vec3& position() const { return m_state.position; }
  const Quaternion& orientation() const { return m_state.orientation; }
  const Vec3& linearMomentum() const { return m_state.linearMomentum; }
  const Vec3& angularMomentum() const { return m_state.angularMomentum; }

  // Derived quantities, recomputed whenever the state changes.
  const Mat3& rotation() const { return m_rotation; }                  // body -> world
  const Mat3& inverseInertiaWorld() const { return m_invInertiaWorld; }  // R Ibody⁻¹ Rᵀ
  Mat3 inertiaWorld() const;                                            // R Ibody Rᵀ
  const Vec3& linearVelocity() const { return m_linearVelocity; }      // m/s, world
  const Vec3& angularVelocity() const { return m_angularVelocity; }    // rad/s, world

  // Velocity of the material point at a world position: v + ω × (p − x).
  Vec3 velocityAtPoint(const Vec3& worldPoint) const;
  Vec3 bodyToWorld(const Vec3& bodyPoint) const { return m_state.position + m_rotation * bodyPoint; }
  Vec3 worldToBody(const Vec3& worldPoint) const {
    return m_rotation.transpose() * (worldPoint - m_state.position);
  }
  double kineticEnergy() const;  // J: ½ P·v + ½ L·ω

  // Replaces the whole state (normalising the quaternion) and the derived
  // values. A finite state also becomes the guard's last good pose (unless
  // the body is frozen: then it is held where it was frozen). Give a finite
  // state: the guard clears free bodies on their momenta and would not see a
  // NaN put straight into the pose.
  void setState(const RigidState& state);
  void setVelocities(const Vec3& linearVelocity, const Vec3& angularVelocity);
  void setDamping(double linear, double angular);


  // Sleeping: a body at rest long enough (with its whole island) is not
  // integrated until something touches or pushes it.
  bool isSleeping() const { return m_sleeping; }

  // Frozen by the numerical guard (world/state_guard.h): held still at its
  // last good pose, never integrated or collided again.
  bool isFrozen() const { return m_freezeReason != FreezeReason::None; }
  FreezeReason freezeReason() const { return m_freezeReason; }

  // What the world's stepping and restoring write; nothing else should.
  void setSerial(int32_t serial) { m_serial = serial; }
  // The stepping paths: the integrator's new state as it is (its quaternion
  // already normalised) and the derived values with it, in one pass.
  void moveTo(const RigidState& state) {
    m_state = state;
    updateDerived();
  }
  void setMomenta(const Vec3& linearMomentum, const Vec3& angularMomentum) {
    m_state.linearMomentum = linearMomentum;
    m_state.angularMomentum = angularMomentum;
    updateDerived();
  }
  void setSleeping(bool sleeping) { m_sleeping = sleeping; }
  double restTime() const { return m_restTime; }  // s below the sleep velocities
  void setRestTime(double restTime) { m_restTime = restTime; }
  void wake() {
    m_sleeping = false;
    m_restTime = 0.0;
  }
  // The numerical guard's bookkeeping (world/state_guard.h).
  const Vec3& lastGoodPosition() const { return m_lastGoodPosition; }
  const Quaternion& lastGoodOrientation() const { return m_lastGoodOrientation; }
  void keepPoseAsGood() {
    m_lastGoodPosition = m_state.position;
    m_lastGoodOrientation = m_state.orientation;
  }
  void setFreezeReason(FreezeReason reason) { m_freezeReason = reason; }
  // Back at the last good pose with zero momenta, awake (a frozen
  // body is not at rest in an island, and waking it must not be what brings
  // it back).
  void holdAtLastGoodPose();

 private:
  void updateDerived();

  std::shared_ptr<const BodyDescription> m_description;
  BodyDynamics m_dynamics;
  RigidState m_state;
  Mat3 m_rotation = Mat3::Identity();
  Mat3 m_invInertiaWorld = Mat3::Zero();
  Vec3 m_linearVelocity = Vec3::Zero();
  Vec3 m_angularVelocity = Vec3::Zero();
  int32_t m_serial = 0;
  bool m_sleeping = false;
  double m_restTime = 0.0;  // s spent below the sleep velocities
  // The pose that last passed the guard's check: where a body that goes bad
  // is put back. Kept by the world after every step and by setState.
  Vec3 m_lastGoodPosition = Vec3::Zero();
  Quaternion m_lastGoodOrientation = Quaternion::identity();
  FreezeReason m_freezeReason = FreezeReason::None;
};

}  // namespace rbsim
