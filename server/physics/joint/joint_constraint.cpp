#include "physics/joint/joint_constraint.h"

#include <cmath>
#include <limits>

namespace rbsim {

namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

// Two unit vectors perpendicular to the unit `axis` and to each other, with
// (n1, n2, axis) right-handed.
void perpendiculars(const Vec3& axis, Vec3& n1, Vec3& n2) {
  const Vec3 helper = std::abs(axis.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  n1 = helper.cross(axis).normalized();
  n2 = axis.cross(n1);
}

// The point-coincidence rows (spherical, revolute, fixed): C = p_B − p_A.
void pointRows(const Vec3& armA, const Vec3& armB, JointRow* out) {
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = Vec3::Unit(k);
    out[k].linearA = -e;
    out[k].angularA = -armA.cross(e);
    out[k].linearB = e;
    out[k].angularB = armB.cross(e);
  }
}

// The error rotation q_B r₀⁻¹ q_A⁻¹, on the short way round (w >= 0).
Quaternion errorRotation(const JointSidePose& a, const JointSidePose& b, const Quaternion& restRelative) {
  const Quaternion e = b.orientation * restRelative.conjugate() * a.orientation.conjugate();
  return e.w < 0.0 ? Quaternion{-e.w, -e.x, -e.y, -e.z} : e;
}

// 2·vec(e), the rotation error as three numbers.
Vec3 rotationError(const JointSidePose& a, const JointSidePose& b, const Quaternion& restRelative) {
  return 2.0 * errorRotation(a, b, restRelative).vec();
}

// The no-relative-rotation rows (fixed, prismatic): the exact derivatives of
// 2·vec(e) for turns δθ of the sides (q → (1 + ½δθ) q, world frame):
// δ(2 vec e) = (e_w 1 − [e_v]×) δθ_B − (e_w 1 + [e_v]×) δθ_A, which is
// δθ_B − δθ_A on the constraint (e = 1).
void rotationRows(const JointSidePose& a, const JointSidePose& b, const Quaternion& restRelative, JointRow* out) {
  const Quaternion e = errorRotation(a, b, restRelative);
  const Vec3 v = e.vec();
  for (int k = 0; k < 3; ++k) {
    const Vec3 axis = Vec3::Unit(k);
    out[k].linearA = Vec3::Zero();
    out[k].angularA = -(e.w * axis - v.cross(axis));  // row k of −(e_w 1 + [e_v]×)
    out[k].linearB = Vec3::Zero();
    out[k].angularB = e.w * axis + v.cross(axis);     // row k of (e_w 1 − [e_v]×)
  }
}

// The row of the anchors' distance |p_B − p_A| (a rod's equality, a rope's
// bounds, a spring's line). A rod whose anchors meet has no direction; any
// will do (the error then is −length and the step pushes them apart along it).
JointRow rodRow(const Vec3& armA, const Vec3& armB, const Vec3& separation) {
  const double distance = separation.norm();
  const Vec3 n = distance > 0.0 ? Vec3(separation / distance) : Vec3::UnitZ();
  return {-n, -armA.cross(n), n, armB.cross(n)};
}

}  // namespace

const char* jointTypeName(JointType type) {
  switch (type) {
    case JointType::Fixed: return "fixed";
    case JointType::Revolute: return "revolute";
    case JointType::Prismatic: return "prismatic";
    case JointType::Spherical: return "spherical";
    case JointType::Distance: return "distance";
  }
  return "unknown";
}

int JointConstraint::rowCount() const {
  switch (def.type) {
    case JointType::Spherical: return 3;
    case JointType::Revolute: return 5;
    case JointType::Prismatic: return 5;
    case JointType::Fixed: return 6;
    case JointType::Distance: return def.limit.enabled || hasSpring() ? 0 : 1;
  }
  return 0;
}

std::string invalidDriveReason(const JointDrive& drive) {
  const auto nonNegative = [](double x) { return std::isfinite(x) && x >= 0.0; };
  if (!std::isfinite(drive.target)) return "the drive's target is not finite";
  if (!std::isfinite(drive.targetRate)) return "the drive's target rate is not finite";
  if (!nonNegative(drive.stiffness) || !nonNegative(drive.damping))
    return "the drive's stiffness and damping must be finite and non-negative";
  if (!nonNegative(drive.frequency) || !nonNegative(drive.dampingRatio))
    return "the drive's frequency and damping ratio must be finite and non-negative";
  if (std::isnan(drive.maxEffort) || drive.maxEffort <= 0.0) return "the drive's max effort must be positive";
  return {};
}

Expected<JointConstraint> makeJointConstraint(const JointDef& def, const JointSidePose& a,
                                              const JointSidePose& b) {
  const std::string where = "joint '" + def.name + "'";
  if (!finite(def.anchor)) return Error{where + ": the anchor is not finite"};
  JointConstraint joint;
  joint.def = def;
  const auto toA = [&](const Vec3& world) { return Vec3(a.rotation.transpose() * (world - a.position)); };
  const auto toB = [&](const Vec3& world) { return Vec3(b.rotation.transpose() * (world - b.position)); };
  joint.anchorA = toA(def.anchor);
  joint.anchorB = toB(def.anchor);
  joint.restRelative = (a.orientation.conjugate() * b.orientation).normalized();
  const bool cone = def.type == JointType::Spherical && def.coneAngle != 0.0;
  if (cone && (!std::isfinite(def.coneAngle) || def.coneAngle <= 0.0 || def.coneAngle >= 3.14159265358979323846))
    return Error{where + ": the cone angle must be in (0, π) rad (got " + std::to_string(def.coneAngle) + ")"};
  if (def.coneAngle != 0.0 && def.type != JointType::Spherical)
    return Error{where + ": only spherical joints take a cone limit"};
  if (def.type == JointType::Revolute || def.type == JointType::Prismatic || cone) {
    const double norm = def.axis.norm();
    if (!std::isfinite(norm) || norm < 1e-9)
      return Error{where + ": the axis must be a finite, non-zero vector"};
    const Vec3 axis = def.axis / norm;
    joint.def.axis = axis;
    joint.axisA = a.rotation.transpose() * axis;
    joint.axisB = b.rotation.transpose() * axis;
    perpendiculars(joint.axisA, joint.normalA1, joint.normalA2);
  }
  const bool axial = def.type == JointType::Revolute || def.type == JointType::Prismatic;
  if (def.limit.enabled) {
    if (!axial && def.type != JointType::Distance)
      return Error{where + ": only revolute, prismatic and distance joints take a limit (a spherical one a cone)"};
    if (!std::isfinite(def.limit.lower) || !std::isfinite(def.limit.upper) || def.limit.lower > def.limit.upper)
      return Error{where + ": the limit needs finite lower <= upper (got " + std::to_string(def.limit.lower) +
                   ", " + std::to_string(def.limit.upper) + ")"};
    if (def.type == JointType::Distance && (def.limit.lower < 0.0 || def.limit.upper <= 0.0))
      return Error{where + ": a rope's lengths need 0 <= lower <= upper, upper > 0 (got " +
                   std::to_string(def.limit.lower) + ", " + std::to_string(def.limit.upper) + ")"};
  }
  if (def.position != 0.0) {
    if (!axial)
      return Error{where + ": only revolute and prismatic joints take a position (their coordinate at creation)"};
    if (!std::isfinite(def.position)) return Error{where + ": the position is not finite"};
  }
  if (def.mimic.enabled) {
    if (!axial) return Error{where + ": only revolute and prismatic joints follow another (mimic)"};
    if (def.mimic.leader.empty()) return Error{where + ": mimic: the leading joint's name is empty"};
    if (def.mimic.leader == def.name) return Error{where + ": mimic: a joint cannot follow itself"};
    if (!std::isfinite(def.mimic.multiplier) || !std::isfinite(def.mimic.offset))
      return Error{where + ": mimic: the multiplier and offset must be finite (got " +
                   std::to_string(def.mimic.multiplier) + ", " + std::to_string(def.mimic.offset) + ")"};
    if (def.motor.enabled || def.drive.enabled || def.effort != 0.0)
      return Error{where + ": follows joint '" + def.mimic.leader +
                   "' (mimic), so it takes no motor, drive or effort of its own: command its leader"};
  }
  if (def.motor.enabled) {
    if (!axial) return Error{where + ": only revolute and prismatic joints take a motor"};
    if (!std::isfinite(def.motor.targetRate) || !std::isfinite(def.motor.maxEffort) || def.motor.maxEffort < 0.0)
      return Error{where + ": the motor needs a finite target rate and a finite, non-negative max effort"};
  }
  if (def.drive.enabled) {
    if (!axial && def.type != JointType::Distance)
      return Error{where + ": only revolute and prismatic joints take a drive (and distance joints a spring)"};
    if (def.motor.enabled) return Error{where + ": a joint takes a motor or a drive, not both"};
    if (const std::string why = invalidDriveReason(def.drive); !why.empty()) return Error{where + ": " + why};
  }
  if (def.damping != 0.0 || def.friction != 0.0) {
    if (!axial) return Error{where + ": only revolute and prismatic joints take damping and friction"};
    if (!std::isfinite(def.damping) || def.damping < 0.0 || !std::isfinite(def.friction) || def.friction < 0.0)
      return Error{where + ": damping and friction must be finite and non-negative"};
  }
  if (def.effort != 0.0) {
    if (!axial) return Error{where + ": only revolute and prismatic joints take an effort"};
    if (!std::isfinite(def.effort)) return Error{where + ": the effort is not finite"};
  }
  const JointActuatorLimits& limits = def.actuatorLimits;
  if (std::isnan(limits.effort) || limits.effort <= 0.0 || std::isnan(limits.rate) || limits.rate <= 0.0)
    return Error{where + ": the actuator's effort and rate limits must be positive (got " +
                 std::to_string(limits.effort) + ", " + std::to_string(limits.rate) + ")"};
  if (!axial && (std::isfinite(limits.effort) || std::isfinite(limits.rate)))
    return Error{where + ": only revolute and prismatic joints take actuator limits"};
  if (def.type == JointType::Distance) {
    if (!finite(def.anchorB)) return Error{where + ": anchor_b is not finite"};
    joint.anchorB = toB(def.anchorB);
    const double initial = (def.anchorB - def.anchor).norm();
    if (joint.hasSpring()) {
      // The spring's rest length is its drive's target (checked above).
      if (def.drive.target < 0.0)
        return Error{where + ": the spring's rest length must not be negative (got " +
                     std::to_string(def.drive.target) + ")"};
      joint.length = def.drive.target;
    } else {
      joint.length = def.length < 0.0 ? initial : def.length;
      if (def.limit.enabled) joint.length = def.limit.upper;  // a rope: its longest
      if (!std::isfinite(joint.length) || joint.length < 1e-9)
        return Error{where + ": the length must be positive and finite (the anchors are " +
                     std::to_string(initial) + " m apart)"};
    }
    joint.def.length = joint.length;
  }
  return joint;
}

JointConstraint::Basis JointConstraint::basisAt(const JointSidePose& a) const {
  Basis basis;
  if (def.type == JointType::Revolute) {
    basis.normal1 = a.rotation * normalA1;
    basis.normal2 = a.rotation * normalA2;
  }
  return basis;
}

void JointConstraint::errors(const JointSidePose& a, const JointSidePose& b, const Basis& basis,
                             double* out) const {
  const Vec3 pA = a.position + a.rotation * anchorA;
  const Vec3 pB = b.position + b.rotation * anchorB;
  const Vec3 separation = pB - pA;
  switch (def.type) {
    case JointType::Spherical:
      for (int k = 0; k < 3; ++k) out[k] = separation[k];
      return;
    case JointType::Revolute: {
      for (int k = 0; k < 3; ++k) out[k] = separation[k];
      const Vec3 misalignment = (a.rotation * axisA).cross(b.rotation * axisB);
      out[3] = misalignment.dot(basis.normal1);
      out[4] = misalignment.dot(basis.normal2);
      return;
    }
    case JointType::Fixed: {
      for (int k = 0; k < 3; ++k) out[k] = separation[k];
      const Vec3 turn = rotationError(a, b, restRelative);
      for (int k = 0; k < 3; ++k) out[3 + k] = turn[k];
      return;
    }
    case JointType::Prismatic: {
      const Vec3 turn = rotationError(a, b, restRelative);
      for (int k = 0; k < 3; ++k) out[k] = turn[k];
      out[3] = separation.dot(a.rotation * normalA1);
      out[4] = separation.dot(a.rotation * normalA2);
      return;
    }
    case JointType::Distance:
      // A rope or a spring has no equality row (rowCount() is 0): its
      // length is held by limitRow() or pulled by the drive alone.
      if (rowCount() == 0) return;
      out[0] = separation.norm() - length;
      return;
  }
}

void JointConstraint::rows(const JointSidePose& a, const JointSidePose& b, const Basis& basis,
                           JointRow* out) const {
  const Vec3 armA = a.rotation * anchorA;  // from A's centre of mass to its anchor
  const Vec3 armB = b.rotation * anchorB;
  const Vec3 pA = a.position + armA;
  const Vec3 pB = b.position + armB;
  switch (def.type) {
    case JointType::Spherical:
      pointRows(armA, armB, out);
      return;
    case JointType::Revolute:
      pointRows(armA, armB, out);
      // The exact derivative of (a_A × a_B)·n: δθ_A·(a_A × (a_B × n)) +
      // δθ_B·(a_B × (n × a_A)), which is n·(δθ_B − δθ_A) on the constraint.
      {
        const Vec3 axisOfA = a.rotation * axisA, axisOfB = b.rotation * axisB;
        for (int k = 0; k < 2; ++k) {
          const Vec3& n = k == 0 ? basis.normal1 : basis.normal2;
          out[3 + k] = {Vec3::Zero(), axisOfA.cross(axisOfB.cross(n)), Vec3::Zero(), axisOfB.cross(n.cross(axisOfA))};
        }
      }
      return;
    case JointType::Fixed:
      pointRows(armA, armB, out);
      rotationRows(a, b, restRelative, out + 3);
      return;
    case JointType::Prismatic: {
      rotationRows(a, b, restRelative, out);
      // d/dt (p_B − p_A)·t with t carried by A: t·(v at p_B of B − v at p_B
      // of A), so A's lever arm reaches to B's anchor.
      const Vec3 armAToB = pB - a.position;
      for (int k = 0; k < 2; ++k) {
        const Vec3 t = a.rotation * (k == 0 ? normalA1 : normalA2);
        out[3 + k] = {-t, -armAToB.cross(t), t, armB.cross(t)};
      }
      return;
    }
    case JointType::Distance:
      if (rowCount() == 1) out[0] = rodRow(armA, armB, pB - pA);  // none for a rope or a spring
      return;
  }
}

bool JointConstraint::axisRow(const JointSidePose& a, const JointSidePose& b, JointRow& out) const {
  const Vec3 axis = a.rotation * axisA;
  if (def.type == JointType::Revolute) {
    out = {Vec3::Zero(), -axis, Vec3::Zero(), axis};
    return true;
  }
  if (def.type == JointType::Prismatic) {
    // d/dt (p_B − p_A)·a with a carried by A (as the prismatic's other rows).
    const Vec3 armB = b.rotation * anchorB;
    const Vec3 armAToB = b.position + armB - a.position;
    out = {-axis, -armAToB.cross(axis), axis, armB.cross(axis)};
    return true;
  }
  return false;
}

double JointConstraint::coordinate(const JointSidePose& a, const JointSidePose& b) const {
  const Vec3 pA = a.position + a.rotation * anchorA;
  const Vec3 pB = b.position + b.rotation * anchorB;
  switch (def.type) {
    case JointType::Revolute: {
      // B's rotation relative to A, from the rest relative orientation, in
      // A's frame; its angle about A's axis.
      const Quaternion turn = a.orientation.conjugate() * b.orientation * restRelative.conjugate();
      return def.position + 2.0 * std::atan2(turn.vec().dot(axisA), turn.w);
    }
    case JointType::Prismatic:
      return def.position + (pB - pA).dot(a.rotation * axisA);
    case JointType::Distance:
      return (pB - pA).norm();
    case JointType::Spherical: {
      if (def.coneAngle <= 0.0) return 0.0;
      const Vec3 u = a.rotation * axisA, v = b.rotation * axisB;
      return std::atan2(u.cross(v).norm(), u.dot(v));
    }
    case JointType::Fixed:
      return 0.0;
  }
  return 0.0;
}

double JointConstraint::limitLower() const {
  return def.type == JointType::Spherical ? -std::numeric_limits<double>::infinity() : def.limit.lower;
}

double JointConstraint::limitUpper() const {
  return def.type == JointType::Spherical ? def.coneAngle : def.limit.upper;
}

void JointConstraint::limitRow(const JointSidePose& a, const JointSidePose& b, JointRow& out) const {
  if (axisRow(a, b, out)) return;
  if (def.type == JointType::Distance) {
    const Vec3 armA = a.rotation * anchorA, armB = b.rotation * anchorB;
    out = rodRow(armA, armB, (b.position + armB) - (a.position + armA));  // as rows() does
    return;
  }
  // The swing: its axis u × v, or any normal to u where the two coincide
  // (no swing: the cone is not reached there unless its angle is 0).
  const Vec3 u = a.rotation * axisA, v = b.rotation * axisB;
  Vec3 n = u.cross(v);
  const double norm = n.norm();
  if (norm > 0.0) {
    n /= norm;
  } else {
    Vec3 other;
    perpendiculars(u, n, other);
  }
  out = {Vec3::Zero(), -n, Vec3::Zero(), n};
}

double JointConstraint::coordinateRate(const JointSidePose& a, const JointSidePose& b, const Vec3& vA,
                                       const Vec3& wA, const Vec3& vB, const Vec3& wB) const {
  const Vec3 pB = b.position + b.rotation * anchorB;
  const Vec3 pA = a.position + a.rotation * anchorA;
  const Vec3 relative = vB + wB.cross(pB - b.position) - vA - wA.cross(pB - a.position);
  switch (def.type) {
    case JointType::Revolute:
      return (wB - wA).dot(a.rotation * axisA);
    case JointType::Prismatic:
      return relative.dot(a.rotation * axisA);
    case JointType::Distance: {
      const Vec3 separation = pB - pA;
      const double distance = separation.norm();
      const Vec3 atA = vA + wA.cross(pA - a.position);
      const Vec3 atB = vB + wB.cross(pB - b.position);
      return distance > 0.0 ? (atB - atA).dot(separation) / distance : 0.0;
    }
    case JointType::Spherical: {
      if (def.coneAngle <= 0.0) return 0.0;
      JointRow row;
      limitRow(a, b, row);
      return row.angularB.dot(wB) + row.angularA.dot(wA);
    }
    case JointType::Fixed:
      return 0.0;
  }
  return 0.0;
}

}  // namespace rbsim
