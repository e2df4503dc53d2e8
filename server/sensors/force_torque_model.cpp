#include "sensors/force_torque_model.h"

namespace rbsim {

ForceTorqueReading readForceTorque(const JointState& joint, const SensorFrame& frame) {
  ForceTorqueReading reading;
  reading.force = frame.toSensor(joint.force);
  reading.torque = frame.toSensor(joint.torque + (joint.anchorB - frame.position).cross(joint.force));
  return reading;
}

}  // namespace rbsim
