#pragma once
// The world: owns the bodies and steps them by a fixed dt.
//
// Determinism: the same sequence of calls gives bit-identical states. Bodies
// are stepped in creation order (kept across removals), no unordered
// container decides an order, and no clock or random source is read here.

#include <cstdint>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "physics/body/body.h"
#include "physics/body/body_def.h"
#include "physics/common/expected.h"
#include "physics/world/body_id.h"
#include "physics/world/world_settings.h"

namespace rbsim {

class World {
 public:
  explicit World(const WorldSettings& settings = {});

  // Builds a whole world; the first bad body stops it with its error.
  static Expected<World> fromDef(const WorldDef& def);

  // Computes the mass properties from the shape (mass or density), puts the
  // body frame at the centre of mass along the principal axes and places it
  // so that the shape lands at def.position / def.orientation. Errors: empty
  // or duplicate name, non-positive or non-finite mass, density or size, a
  // plane on a dynamic body, a mesh that is missing.
  Expected<BodyId> createBody(const BodyDef& def);
  bool removeBody(BodyId id);  // false for a null or stale id

  BodyId findBody(std::string_view name) const;  // null id when absent
  bool isValid(BodyId id) const;
  const Body& body(BodyId id) const;  // asserts isValid
  Body& body(BodyId id);
  BodyId idOf(int denseIndex) const { return m_denseIds[static_cast<size_t>(denseIndex)]; }

  // Bodies in creation order; the vector's index is a body's dense index,
  // which changes when an earlier body is removed (the BodyId does not).
  const std::vector<Body>& bodies() const { return m_bodies; }
  int bodyCount() const { return static_cast<int>(m_bodies.size()); }

  // Advances every dynamic body by dt with the world's integrator, applying
  // gravity, damping and the external loads given since the last step, then
  // clears those loads.
  void step();

  const WorldSettings& settings() const { return m_settings; }
  void setGravity(const Vec3& gravity) { m_settings.gravity = gravity; }
  void setIntegrator(IntegratorKind kind) { m_settings.integrator = kind; }
  int64_t stepCount() const { return m_stepCount; }
  double time() const { return static_cast<double>(m_stepCount) * m_settings.dt; }  // s

  // Total linear and angular momentum (about the world origin) and kinetic
  // energy of the dynamic bodies.
  Vec3 totalLinearMomentum() const;
  Vec3 totalAngularMomentum() const;
  double totalKineticEnergy() const;

  // FNV-1a over the bit patterns of every body's (x, q, P, L) and the step
  // count: equal hashes mean bit-identical states.
  uint64_t stateHash() const;

 private:
  struct Slot {
    uint32_t generation = 0;
    int32_t denseIndex = -1;  // -1: free
  };

  WorldSettings m_settings;
  std::vector<Body> m_bodies;      // dense, in creation order
  std::vector<BodyId> m_denseIds;  // parallel to m_bodies
  std::vector<Slot> m_slots;
  std::vector<int32_t> m_freeSlots;  // reused lowest-first, for determinism
  // Name lookup only; never iterated, so its order cannot leak into a step.
  std::unordered_map<std::string, BodyId> m_idByName;
  int64_t m_stepCount = 0;
  int32_t m_lastSerial = 0;
};

}  // namespace rbsim
