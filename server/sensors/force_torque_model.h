#pragma once
// A force–torque sensor at a joint: the reaction the joint applied to its
// child body (body B) over the last step, as the joint state reports it
// (World::jointState: the constraint impulses / dt, the couple about B's
// anchor), moved to the sensor's origin (τ_o = τ_anchor + (anchor − o) × F)
// and turned into the sensor frame.

#include "rbsim/physics/joint_definition.h"
#include "sensors/sensor_frame.h"
#include "sensors/sensor_reading.h"

namespace rbsim {

ForceTorqueReading readForceTorque(const JointState& joint, const SensorFrame& frame);

}  // namespace rbsim
