#include "sensors/contact_model.h"

namespace rbsim {

ContactReading readContacts(const World& world, const BodyView& body, const SensorFrame& frame) {
  const int32_t serial = body.serial();
  const double inverseDt = 1.0 / world.settings().dt;
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  ContactReading reading;
  for (const SolvedManifold& manifold : world.contacts()) {
    // The impulses are those on body B; body A got the opposite.
    double sign = 0.0;
    if (manifold.serialB == serial) sign = 1.0;
    else if (manifold.serialA == serial) sign = -1.0;
    else continue;
    for (int p = 0; p < manifold.pointCount; ++p) {
      const SolvedContactPoint& point = manifold.points[p];
      const Vec3 pointForce =
          sign * inverseDt * (point.normalImpulse * manifold.normal + point.tangentImpulse);
      force += pointForce;
      torque += (point.point - frame.position).cross(pointForce);
    }
    torque += sign * inverseDt * manifold.twistImpulse * manifold.normal;
    reading.contacts += manifold.pointCount;
  }
  reading.force = frame.toSensor(force);
  reading.torque = frame.toSensor(torque);
  return reading;
}

}  // namespace rbsim
