#pragma once
// The geometry of one joint: its data in each body's frame, its position
// constraints C(x) = 0 (a joint type is a set of scalar rows) and their
// Jacobians, the rows of J in J v = dC/dt.
//
// Rows per type:
//   spherical  3: the anchors coincide, C = p_B − p_A
//   revolute   5: the anchors coincide, and the axes stay aligned: two rows
//                 (a_A × a_B)·t_k with t_1, t_2 perpendicular to the axis
//   prismatic  5: no relative rotation (3), and p_B − p_A stays on the axis
//                 carried by A: (p_B − p_A)·t_k, t_k perpendicular to it (2)
//   fixed      6: the anchors coincide (3), no relative rotation (3)
//   distance   1: |p_B − p_A| − length; none for a rope (a distance joint
//                 with a limit: only its bounds, as inequalities) or a
//                 spring (its drive acts along the anchors' line)
// "No relative rotation" is the error rotation e = q_B r₀⁻¹ q_A⁻¹ (r₀ the
// relative orientation at creation) as the 3 numbers 2·vec(e), whose rate is
// ω_B − ω_A near e = 1.

#include <array>
#include <string>

#include "rbsim/physics/expected.h"
#include "rbsim/physics/quaternion.h"
#include "rbsim/physics/math_types.h"
#include "rbsim/physics/joint_definition.h"

namespace rbsim {

constexpr int kMaxJointRows = 6;

// Where one side of a joint is: a body's centre of mass and orientation, or
// the world's origin and axes.
struct JointSidePose {
  Vec3 position = Vec3::Zero();
  Quaternion orientation = Quaternion::identity();
  Mat3 rotation = Mat3::Identity();
};

// One scalar constraint row between the two sides: its velocity is
//   linearA·v_A + angularA·ω_A + linearB·v_B + angularB·ω_B,
// and an impulse λ along it changes the momenta by
//   P_A += λ linearA, L_A += λ angularA, P_B += λ linearB, L_B += λ angularB.
struct JointRow {
  Vec3 linearA = Vec3::Zero();
  Vec3 angularA = Vec3::Zero();
  Vec3 linearB = Vec3::Zero();
  Vec3 angularB = Vec3::Zero();
};

// A joint as the world keeps it: the definition and its data in the bodies'
// frames (the world frame for a side that is the world).
struct JointConstraint {
  JointDef def;
  Vec3 anchorA = Vec3::Zero();  // in A's body frame
  Vec3 anchorB = Vec3::Zero();  // in B's body frame
  Vec3 axisA = Vec3::UnitZ();   // unit, in A's body frame
  Vec3 axisB = Vec3::UnitZ();   // unit, in B's body frame
  Vec3 normalA1 = Vec3::UnitX(), normalA2 = Vec3::UnitY();  // ⟂ axisA, in A's frame
  Quaternion restRelative = Quaternion::identity();  // q_A⁻¹ q_B at creation
  double length = 0.0;                               // distance joints, m

  // The joint's result over the last step, for JointState.
  Vec3 lastForce = Vec3::Zero();   // N, on B, world
  Vec3 lastTorque = Vec3::Zero();  // N·m, on B about its anchor, world

  int rowCount() const;

  // The directions the revolute's two angular rows project on, fixed for a
  // step: perpendicular to A's axis at the step's start.
  struct Basis {
    Vec3 normal1 = Vec3::UnitX(), normal2 = Vec3::UnitY();
  };
  Basis basisAt(const JointSidePose& a) const;

  // C(x) at the poses, rowCount() values.
  void errors(const JointSidePose& a, const JointSidePose& b, const Basis& basis, double* out) const;
  // The rows of J at the poses, rowCount() of them: the exact derivatives of
  // errors() for velocities and turns of the sides (at any poses, on the
  // constraint or off it), so a Newton iteration on C can use them.
  void rows(const JointSidePose& a, const JointSidePose& b, const Basis& basis, JointRow* out) const;

  // Revolute and prismatic: the row of the joint coordinate (its exact
  // derivative on the joint: ω_B − ω_A along A's axis, or the relative
  // velocity at B's anchor along it), through which limits, motors and
  // efforts act. False for the other types.
  bool axisRow(const JointSidePose& a, const JointSidePose& b, JointRow& out) const;
  bool hasAxis() const { return def.type == JointType::Revolute || def.type == JointType::Prismatic; }
  // A distance joint with a drive: a spring–damper between the anchors,
  // rest length def.drive.target, acting along limitRow().
  bool hasSpring() const { return def.type == JointType::Distance && def.drive.enabled; }

  // A bound on coordinate() held as an inequality: a revolute's or
  // prismatic's limit, a rope's (a distance joint with a limit) lengths, a
  // spherical joint's cone (an upper bound on the swing).
  bool hasLimit() const { return def.limit.enabled || (def.type == JointType::Spherical && def.coneAngle > 0.0); }
  double limitLower() const;
  double limitUpper() const;
  // The exact derivative of coordinate() there: axisRow() for an axis, the
  // rod's row for a distance, (ω_B − ω_A)·(u × v)/|u × v| for a swing
  // between u (the cone's axis on A) and v (on B).
  void limitRow(const JointSidePose& a, const JointSidePose& b, JointRow& out) const;

  // Last step's actuation and limit, for JointState.
  double lastAxisEffort = 0.0;
  int lastAtLimit = 0;

  // A follower (def.mimic): its leader, and the coupling's error (position
  // − multiplier · leader's − offset) at the end of the last step, which
  // the next step counts the coordinates' changes from (joint_solver.h's
  // couplings): a revolute's coordinate wraps, the coupling must not.
  JointId mimicLeader;
  double mimicError = 0.0;  // rad or m

  // A drive's gravity compensation for the step (def.drive.
  // gravityCompensation), computed from the state at its start.
  double gravityFeedForward = 0.0;  // N·m or N

  // The joint coordinate and its rate (JointState::position, rate) from the
  // poses and the sides' velocities; an axis's coordinate counts from
  // def.position at creation, as its limits and drive target do.
  double coordinate(const JointSidePose& a, const JointSidePose& b) const;
  double coordinateRate(const JointSidePose& a, const JointSidePose& b, const Vec3& vA, const Vec3& wA,
                        const Vec3& vB, const Vec3& wB) const;
};

// Builds the joint's body-frame data from its definition (world frame,
// initial configuration) and the sides' poses. Errors name the joint and the
// field: a non-finite anchor, a zero or non-finite axis, a rod of zero or
// negative length, a limit, motor or effort on a joint without an axis or
// with bad numbers (not finite, lower above upper, a negative effort cap),
// a motor and a drive together, damping or friction on a joint without an
// axis, or negative, a position on a joint without an axis or not finite;
// a mimic on a joint without an axis, without a leader's name, with a
// multiplier or offset that is not finite, or on a joint that has a motor,
// a drive or an effort of its own. (A position beyond the limits is
// accepted: the limit brings the joint back.)
// Why a drive's numbers are bad (empty: they are not): a target that is not
// finite, a negative or non-finite stiffness, damping, frequency or damping
// ratio, a max effort that is not positive.
std::string invalidDriveReason(const JointDrive& drive);

Expected<JointConstraint> makeJointConstraint(const JointDef& def, const JointSidePose& a,
                                              const JointSidePose& b);

}  // namespace rbsim
