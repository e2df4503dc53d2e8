#pragma once
// Joints: what a user gives to join two bodies (JointDef), and what the world
// reports of a joint (JointState). A joint joins two bodies, or a body and
// the world (a null BodyId, or a static body).
//
// Every point and direction is given in the world frame, in the initial
// configuration: the world turns them into each body's frame when the joint
// is created, so "the hinge is here, along this axis, now" is all a user has
// to know. Units are SI; angles in rad.
//
// The joints are solved at the position level (docs/joints_design.md): each
// step ends with the joints closed to rounding (about 1e-12 m and rad) and
// the velocities tangent to them, whatever the mass ratios.

#include <limits>
#include <string>

#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/ids.h"

namespace rbsim {

enum class JointType {
  Fixed,      // a weld: no relative motion
  Revolute,   // a hinge: rotation about `axis` through `anchor`
  Prismatic,  // a slider: translation along `axis`, no relative rotation
  Spherical,  // a ball joint: rotation about `anchor`
  Distance,   // a rod: `anchor` on A and `anchorB` on B kept `length` apart
};

// "fixed", "revolute", ... as written in config files and messages.
const char* jointTypeName(JointType type);

// Revolute and prismatic joints: bounds on the joint coordinate
// (JointState::position); distance joints: bounds on the anchors' distance,
// which makes the joint a rope or a range instead of a rod (free between
// lower and upper). Held at the position level: the joint stops at a bound
// (inelastically) and pushes back only.
struct JointLimit {
  bool enabled = false;
  double lower = 0.0;  // rad or m
  double upper = 0.0;  // rad or m, >= lower
};

// Revolute and prismatic joints: a velocity motor drives the joint rate to
// `targetRate` with a force or torque along the axis of at most
// `maxEffort` (a wheel's motor, a conveyor).
struct JointMotor {
  bool enabled = false;
  double targetRate = 0.0;  // rad/s or m/s
  double maxEffort = 0.0;   // N·m or N, >= 0
};

// Revolute and prismatic joints: a position drive pulls the joint coordinate
// to `target` as a spring and damper along the axis (a servo, a PD
// controller): effort = −stiffness (position − target) − damping (rate −
// targetRate), capped at `maxEffort`; a target rate lets the damper follow
// a trajectory's velocity instead of holding the joint still (a PD
// controller's q̇_d). The spring and damper are implicit in the step
// (as Box2D's and Jolt's soft constraints), so any stiffness is stable.
// On a distance joint the drive is a spring between the anchors: `target`
// is its rest length (m, >= 0), and the joint has no rigid length (only
// its limits, if any, as stops).
// Instead of stiffness and damping, a drive may give its natural frequency
// and damping ratio: the stiffness and damping then follow each step from
// the effective mass or inertia the axis moves (m ω², 2 ζ m ω).
struct JointDrive {
  bool enabled = false;
  double target = 0.0;        // rad or m
  double stiffness = 0.0;     // N·m/rad or N/m, >= 0
  double damping = 0.0;       // N·m·s/rad or N·s/m, >= 0
  double frequency = 0.0;     // Hz, >= 0; > 0: used instead of stiffness and damping
  double dampingRatio = 0.0;  // with frequency: 1 is critical damping
  double maxEffort = std::numeric_limits<double>::infinity();  // N·m or N, > 0
  // Revolute and prismatic joints: the drive adds, as feed-forward, the
  // effort that holds against gravity everything the joint carries (the
  // bodies beyond it, reached through the other joints without passing a
  // static body or the world) in the configuration at the step's start,
  // as MuJoCo's gravcomp and Gazebo's controllers do: a servo then holds
  // its target without the sag its stiffness would leave. Nothing for a
  // joint whose bodies close a loop back to its own side. Within the
  // actuator's effort limit, with the direct effort.
  bool gravityCompensation = false;
  double targetRate = 0.0;  // rad/s or m/s, finite (last: the aggregate initialisers above stay valid)
};

// Revolute and prismatic joints: what the joint's actuator can give at
// most, whatever it is commanded (URDF's <limit effort velocity>): the
// motor's and the drive's effort and the direct effort are each capped at
// `effort`; the motor's target rate is capped at `rate`, and the drive
// stops pushing the joint faster than `rate` (a servo slews at its top
// speed). Gravity, contacts and a joint's own stops may still move it
// faster: these bound the actuator, not the joint.
struct JointActuatorLimits {
  double effort = std::numeric_limits<double>::infinity();  // N·m or N, > 0
  double rate = std::numeric_limits<double>::infinity();    // rad/s or m/s, > 0
};

// Revolute and prismatic joints: a joint that follows another's coordinate
// (URDF's <mimic>, a gear pair, a gripper's second finger):
//   position = multiplier · leader's position + offset,
// held exactly as one more constraint row of the joint solver, between the
// bodies of both joints. The leader is any revolute or prismatic joint
// created before the follower; commanding the leader moves both, and the
// follower takes no motor, drive or effort of its own (its damping and
// friction still act). Removing the leader frees the follower.
struct JointMimic {
  bool enabled = false;
  std::string leader;       // the leading joint's name
  double multiplier = 1.0;  // (rad or m) per (rad or m); a gear's ratio with its sign
  double offset = 0.0;      // rad or m
};

struct JointDef {
  std::string name;  // unique among the world's joints
  JointType type = JointType::Revolute;
  BodyId bodyA;  // null: the world
  BodyId bodyB;  // null: the world (one of the two must move)
  Vec3 anchor = Vec3::Zero();     // m, world: the joint's point (on A, for a distance joint)
  Vec3 axis = Vec3::UnitZ();      // revolute and prismatic: the joint axis; spherical: the cone's (normalised here)
  Vec3 anchorB = Vec3::Zero();    // m, world: distance joints only, the point on B
  // Distance joints: the rod's length; negative: the anchors' distance at
  // creation.
  double length = -1.0;  // m
  // Whether the two bodies still collide with each other (by default they
  // do not: the links of a chain overlap at their joints).
  bool collideConnected = false;
  // Revolute and prismatic joints: the joint coordinate (JointState::
  // position) in the configuration the joint is created in. A robot
  // description (URDF) measures its joints from its own zero pose and places
  // the bodies at their positions: created so, the joint reads `position`
  // there, and its limits and drive target count from the same zero. A
  // position beyond the limits is where the bodies are: the limit then
  // pushes the joint back to its bound over a few steps by moving the
  // positions only (no velocity, so no energy, comes of it), as descriptions
  // whose zero pose lies outside a limit expect (PyBullet, MuJoCo).
  double position = 0.0;  // rad or m
  // Revolute, prismatic and distance joints (a distance joint with a limit
  // has no `length`: it is free between the bounds, or its spring pulls).
  JointLimit limit;
  // Spherical joints: > 0 limits the swing, the angle between `axis` as A
  // carries it and as B carries it, to at most this (a shoulder, a hip).
  double coneAngle = 0.0;  // rad, < π
  // The motor and the drive are two ways to command the axis: at most one
  // is enabled (a distance joint takes only the drive, as its spring).
  JointMotor motor;
  JointDrive drive;
  // The joint's own losses, as URDF's <dynamics>: viscous damping (an
  // effort −damping · rate) and dry friction (an effort of at most
  // `friction` against the motion, holding the joint still below it).
  double damping = 0.0;   // N·m·s/rad or N·s/m, >= 0
  double friction = 0.0;  // N·m or N, >= 0
  // A force or torque along the axis, on B (and its reaction on A), as a
  // torque-controlled actuator commands it: N·m or N, until changed.
  double effort = 0.0;
  JointActuatorLimits actuatorLimits;
  JointMimic mimic;
};

// A joint as a world file gives it: its bodies by name. World::fromDef
// resolves the names and prefixes any error with `source`.
struct NamedJointDef {
  JointDef def;       // bodyA and bodyB are left null: named below
  std::string bodyA;  // a body's name, or "world"
  std::string bodyB;
  std::string source;  // where it was given, for messages ("world.yaml:12:5: joints[0]")
};

// What a joint is doing after the last step.
struct JointState {
  std::string name;
  JointType type = JointType::Revolute;
  BodyId bodyA, bodyB;  // null: the world
  // The joint coordinate: JointDef::position plus the angle of B about the
  // axis relative to A since the initial configuration (revolute, rad,
  // right-handed about the axis), or plus B's displacement along the axis
  // since then (prismatic, m); the anchors' distance (distance, m), the
  // swing from the cone's axis (spherical with a cone limit, rad); 0 for
  // the others.
  double position = 0.0;
  double rate = 0.0;  // its time derivative: rad/s or m/s
  // B's orientation relative to A's, from the initial configuration
  // (identity there): q_A⁻¹ q_B r₀⁻¹ in A's frame; a spherical joint's
  // position.
  Quaternion rotation = Quaternion::identity();
  Vec3 anchorA = Vec3::Zero();  // m, world: the anchor on A now
  Vec3 anchorB = Vec3::Zero();  // m, world: on B now (equal to anchorA but for rounding, or a rod's length away)
  Vec3 axis = Vec3::UnitZ();    // world: the axis as A carries it
  // The largest violation of the joint's position constraints now (m or rad).
  double error = 0.0;
  // Force and couple the joint applied to B over the last step (N, N·m,
  // world; the couple about B's anchor): the constraint impulses / dt.
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  // The actuation along the axis over the last step (the motor's or the
  // drive's, and the direct effort, as the actuator limits let them act):
  // N·m or N on B. Damping and friction are not in it.
  double axisEffort = 0.0;
  // At a limit after the last step: -1 at the lower one, +1 at the upper, 0 within.
  int atLimit = 0;
  // False while one of its bodies is frozen by the numerical guard: the
  // joint is then not enforced.
  bool active = true;
};

}  // namespace rbsim
