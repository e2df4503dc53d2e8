#include "sensors/imu_model.h"

namespace rbsim {

ImuReading readImu(const BodyView& body, const SensorFrame& frame, const BodyVelocities& before,
                   const Vec3& gravity, double dt) {
  const Vec3& omega = body.angularVelocity();
  const Vec3 centreAcceleration = (body.linearVelocity() - before.linear) / dt;
  const Vec3 angularAcceleration = (omega - before.angular) / dt;
  const Vec3 r = frame.position - body.position();
  const Vec3 pointAcceleration =
      centreAcceleration + angularAcceleration.cross(r) + omega.cross(omega.cross(r));
  ImuReading reading;
  reading.linearAcceleration = frame.toSensor(pointAcceleration - gravity);
  reading.angularVelocity = frame.toSensor(omega);
  reading.orientation = frame.orientation;
  return reading;
}

}  // namespace rbsim
