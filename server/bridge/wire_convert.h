#pragma once
// Conversions between the physics library's values and the LCM wire types.
// Pure functions: no LCM handle, no clock (the caller passes utime).

#include <cstdint>
#include <string>
#include <vector>

#include <rbsim/ack_t.hpp>
#include <rbsim/contacts_t.hpp>
#include <rbsim/joint_command_t.hpp>
#include <rbsim/joints_t.hpp>
#include <rbsim/status_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <rbsim/world_t.hpp>
#include <rbsim/wrench_t.hpp>

#include "config/server_settings.h"
#include "rbsim/physics/types.h"
#include "rbsim/physics/world.h"
#include "robot/visual.h"
#include "session/joint_command_scheduler.h"
#include "session/wrench_scheduler.h"

namespace rbsim {

// Largest payload we put in one LCM message: LCM sends a message as one UDP
// datagram when its header, channel and payload fit in 65499 bytes, and
// fragments it otherwise (docs/lcm.md, "Message size and fragmentation").
// Under that, a page is never fragmented and a lost datagram loses one page,
// not a whole state.
constexpr std::size_t kMaxPagePayloadBytes = 60000;

// The world's state split into pages of whole bodies, each page encoding to
// at most kMaxPagePayloadBytes. Bodies go in creation order (ascending id).
std::vector<rbsim::world_state_t> worldStatePages(const World& world, int64_t utime,
                                                  int64_t revision);

// The world's description, paged the same way (meshes make bodies large),
// with the joints after the bodies (world_t); each body with the visuals of
// its name in `visuals` (null: none).
std::vector<rbsim::world_t> worldDescriptionPages(const World& world, int64_t utime,
                                                  int64_t revision, const BodyVisuals* visuals = nullptr);

// The last step's contact points (positions, normals A→B, depths, solved
// impulses, classification by relative normal velocity), paged like the
// state. Bodies are named by their ids (serials).
std::vector<rbsim::contacts_t> contactPages(const World& world, int64_t utime);

// Every joint's state (joints_t), paged like the state, in creation order.
std::vector<rbsim::joints_t> jointStatePages(const World& world, int64_t utime, int64_t revision);

// Checks a joint command against the world and the limits (max_torque and
// max_force bound a revolute's and a prismatic's efforts, as for wrenches);
// on success the request is ready for the JointCommandScheduler. Errors
// name the field. A velocity command without max_effort (0) takes the
// joint's effort limit (its actuator's, URDF's <limit effort>), and is
// refused when the joint has none: a motor with no effort would be accepted
// and do nothing.
Expected<JointCommandRequest> jointCommandRequestFrom(const rbsim::joint_command_t& message,
                                                      const World& world, int64_t nextStep,
                                                      const WrenchLimits& limits);

// "unknown joint 'x'" and "unknown body 'x'" with the world's closest names
// ("... (did you mean 'y'?)"), for every refusal of a name.
std::string unknownJointReason(const World& world, const std::string& name);
std::string unknownBodyReason(const World& world, const std::string& name);

// Checks a wrench message against the world and the limits; on success the
// request is ready for the WrenchScheduler. `nextStep` is the step the
// server takes next (world.stepCount() + 1).
Expected<WrenchRequest> wrenchRequestFrom(const rbsim::wrench_t& message, const World& world,
                                          int64_t nextStep, const WrenchLimits& limits);

}  // namespace rbsim
