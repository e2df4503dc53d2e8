#include "physics/world/penalty_contact.h"

#include <algorithm>

namespace rbsim {

PenaltyPoint makePenaltyPoint(int bodyA, int bodyB, const BodyMotion& motionA,
                              const BodyMotion& motionB, const Vec3& pointA, const Vec3& pointB,
                              double depth, const Vec3& normal) {
  PenaltyPoint point;
  point.bodyA = bodyA;
  point.bodyB = bodyB;
  point.localA = motionA.rotation.transpose() * (pointA - motionA.position);
  point.localB = motionB.rotation.transpose() * (pointB - motionB.position);
  point.normal = normal;
  // The narrow phase's depth is n · (pA − pB) up to its own rounding; the
  // offset makes d at the detected state exactly the reported depth.
  point.depthOffset = depth - normal.dot(pointA - pointB);
  return point;
}

PenaltyGap penaltyGap(const PenaltyPoint& point, const BodyMotion& motionA,
                      const BodyMotion& motionB) {
  PenaltyGap gap;
  gap.pointA = motionA.position + motionA.rotation * point.localA;
  gap.pointB = motionB.position + motionB.rotation * point.localB;
  gap.depth = point.depthOffset + point.normal.dot(gap.pointA - gap.pointB);
  gap.relativeVelocity = motionB.velocityAt(gap.pointB) - motionA.velocityAt(gap.pointA);
  gap.normalVelocity = point.normal.dot(gap.relativeVelocity);
  return gap;
}

bool penaltyPushes(PenaltyLaw law, const PenaltyPoint& point, const PenaltyGap& gap) {
  if (gap.depth <= 0.0) return false;
  return law == PenaltyLaw::Unclamped || linearPenaltyForce(point, gap) > 0.0;
}

PenaltyForce penaltyForce(const PenaltyPoint& point, const PenaltyGap& gap, bool pushing) {
  PenaltyForce force;
  force.point = 0.5 * (gap.pointA + gap.pointB);
  if (!pushing) return force;
  force.normal = linearPenaltyForce(point, gap);
  const Vec3 tangential = gap.relativeVelocity - gap.normalVelocity * point.normal;
  const double slip = tangential.norm();
  if (slip > 0.0) {
    const double magnitude =
        std::min(point.friction * std::max(0.0, force.normal), point.frictionDamping * slip);
    force.friction = -magnitude / slip * tangential;
  }
  force.onB = force.normal * point.normal + force.friction;
  return force;
}

}  // namespace rbsim
