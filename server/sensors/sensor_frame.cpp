#include "sensors/sensor_frame.h"

namespace rbsim {

SensorFrame sensorFrame(const BodyView& body, const SensorDef& sensor) {
  const BodyDescription& description = body.description();
  SensorFrame frame;
  frame.position = body.bodyToWorld(description.shapeToBodyPoint(sensor.position));
  // config frame -> body frame -> world.
  frame.orientation = (body.orientation() * Quaternion::fromRotationMatrix(description.shapeRotation) *
                       sensor.orientation)
                          .normalized();
  frame.rotation = frame.orientation.toRotationMatrix();
  return frame;
}

}  // namespace rbsim
