// The penalty model's step: spring–damper contact forces.
#include <algorithm>
#include <cmath>

#include "physics/body/integrator.h"
#include "physics/collision/collision_detector.h"
#include "physics/world/world.h"

namespace rbsim {

void World::stepPenalty() {
  // Spring–damper forces from the penetration (the seed's penalty method):
  // along the normal F = k d − c v_n (never pulling), tangentially a viscous
  // force capped at the Coulomb limit μ F_n. Stiffness and damping are per
  // manifold and shared by its points, so a resting body sinks by m g / k
  // whatever its number of contact points. The forces are computed at the
  // step start and held over the step, for every integrator.
  const double dt = m_settings.dt;
  const ContactConfig& config = m_settings.contact;
  findContacts();
  std::vector<SolvedManifold> records;
  records.reserve(m_detector->contacts().size());
  for (const BodyContact& c : m_detector->contacts()) {
    Body& a = m_bodies[static_cast<std::size_t>(c.bodyA)];
    Body& b = m_bodies[static_cast<std::size_t>(c.bodyB)];
    const PairMaterial material = combineMaterials(a.description().material, b.description().material);
    const ContactManifold& m = c.manifold;
    const double share = 1.0 / std::max(1, m.pointCount);
    SolvedManifold record = SolvedManifold::identityOf(c, a.m_serial, b.m_serial);
    for (int p = 0; p < m.pointCount; ++p) {
      const ContactPoint& point = m.points[static_cast<std::size_t>(p)];
      SolvedContactPoint& out = record.points[p];
      const Vec3 x = 0.5 * (point.pointA + point.pointB);
      const Vec3 vRel = b.velocityAtPoint(x) - a.velocityAtPoint(x);
      const double vn = vRel.dot(m.normal);
      out.point = x;
      out.depth = point.depth;
      out.relativeNormalVelocity = vn;
      out.featureId = point.featureId;
      if (point.depth <= 0.0) continue;
      const double normalForce =
          share * config.penaltyStiffness * point.depth - share * config.penaltyDamping * vn;
      if (normalForce <= 0.0) continue;
      const Vec3 vt = vRel - vn * m.normal;
      const double slip = vt.norm();
      Vec3 friction = Vec3::Zero();
      if (slip > 0.0) {
        const double magnitude =
            std::min(material.friction * normalForce, share * config.penaltyFrictionDamping * slip);
        friction = -magnitude / slip * vt;
      }
      const Vec3 force = normalForce * m.normal + friction;  // on B; the opposite on A
      if (!b.isStatic()) b.applyWorldWrench(force, Vec3::Zero(), x);
      if (!a.isStatic()) a.applyWorldWrench(-force, Vec3::Zero(), x);
      out.normalImpulse = normalForce * dt;
      out.tangentImpulse = friction * dt;
      out.sticking = slip < config.solver.stickVelocity;
    }
    records.push_back(record);
  }
  for (Body& body : m_bodies) {  // the penalty model does not sleep bodies
    body.m_sleeping = false;
  }
  integrateFree(dt, {});
  m_contacts = std::move(records);
}

}  // namespace rbsim
