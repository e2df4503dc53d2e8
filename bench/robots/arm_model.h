// The arm of the benchmark from its URDF, through rbsim's loader: the world
// rbsim steps, and the same arm as plain data (arm_bench.h) for the other
// engines. Everything comes from one load of config/robots/arm7.urdf, so
// the engines are given the same masses, principal inertias, poses and
// joint frames to the last bit.
#pragma once

#include "arm_bench.h"
#include "rbsim/physics/world_settings.h"

namespace rbsim::bench::robots {

// arm7.urdf on a fixed base, in the start pose of config/worlds/robot_arm.yaml
// (joint2 0.6, joint4 1.2, joint6 0.8 rad), for the arm benchmark: dt 1 ms,
// gravity on, no contacts (no link collides), no sleeping, and each joint
// without the URDF's damping, friction, stops and actuator limits, so
// that every engine runs the PD law alone (the other engines would each
// model those differently, if at all). Exits with the loader's message if
// the URDF is refused.
WorldDef armWorldDef();

// The same arm as plain data: the static base, the moving links (centre of
// mass and principal axes, as rbsim places them), the joints, their PD
// gains (kNaturalFrequency, kDampingRatio on the inertia each joint moves
// in the start pose with the others free) and the sinusoids' frequencies.
ArmScene armScene();

}  // namespace rbsim::bench::robots
