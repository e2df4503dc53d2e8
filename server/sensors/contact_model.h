#pragma once
// A contact (touch) sensor: what every contact of the last step did to one
// body, from the contact solver's impulses (World::contacts(), the same
// numbers RBSIM_CONTACTS carries): each point's normal and friction
// impulse at the point, and a patch's twisting couple about its normal,
// divided by dt.

#include "rbsim/physics/body_view.h"
#include "rbsim/physics/world.h"
#include "sensors/sensor_frame.h"
#include "sensors/sensor_reading.h"

namespace rbsim {

// Force and torque about the sensor's origin, in the sensor frame; no noise.
ContactReading readContacts(const World& world, const BodyView& body, const SensorFrame& frame);

}  // namespace rbsim
