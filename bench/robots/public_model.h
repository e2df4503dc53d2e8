// The public robots' scenes in rbsim: each scene as a world file (YAML
// text, the form a user writes), loaded by rbsim's config loader, and the
// drives' gains every engine uses, worked out from the robot as rbsim
// loads it.
#pragma once

#include <string>
#include <vector>

#include "public_scenes.h"
#include "rbsim/physics/world_settings.h"

namespace rbsim::bench::robots {

// The scene as a world file: the ground, the table and its objects, the
// robot (merge_fixed_links: true, joint_positions at the start pose,
// joint_drives with `gains` when given) and, when `selfCollisionKey`, the
// robot's `self_collision:` key with the scene's setting.
std::string publicWorldYaml(const PublicScene& s, const std::vector<JointGains>& gains,
                            bool selfCollisionKey);

struct PublicWorld {
  WorldDef def;
  // Empty, or why the scene's self-collision setting could not be given
  // (a tree whose loader does not know `self_collision:` yet: there every
  // pair of links not joined by a joint collides, whatever is asked).
  std::string note;
  std::string yaml;  // the text that was loaded
};

// Loads the scene's world file; exits with the loader's message when it is
// refused.
PublicWorld loadPublicWorld(const PublicScene& s, const std::vector<JointGains>& gains);

// Each driven joint's gains: stiffness I ω², damping 2 ζ I ω, with ω =
// 2π s.naturalFrequency, ζ = s.dampingRatio and I = 1 / (M⁻¹)_kk the
// inertia (or mass) the joint moves with the other joints free in the
// start pose (M the joint-space mass matrix of the robot's moving links,
// the root held still). As arm_model.cpp explains, gains on 1 / (M⁻¹)_kk
// keep an explicit PD (Bullet's and MuJoCo's efforts) stable at dt = 1 ms.
std::vector<JointGains> publicGains(const PublicScene& s);

// The mass properties of the robot's root body as rbsim makes it (the root
// link with the links fixed to it merged), in the root link's frame: for
// engines that lose them on import (MuJoCo welds a URDF's root link to the
// world; a floating base needs them back).
struct RootInertial {
  double mass = 0;
  Vec3 centre{0, 0, 0};  // m
  Quat axes{1, 0, 0, 0};  // principal axes -> root link frame
  Vec3 moments{0, 0, 0};  // kg m²
};
RootInertial rootInertial(const PublicScene& s);

}  // namespace rbsim::bench::robots
