#pragma once
// Worlds for the joint tests: gravity along −z, no ground, the integrator
// and step asked for; bodies made from a shape and a mass; hinges and
// sliders, and why a joint was refused; the energy of a world; the
// crossings of a signal through zero.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rbsim/physics/world.h"

namespace rbsim::testing {

constexpr double kGravity = 9.81;

inline WorldSettings jointWorldSettings(IntegratorKind integrator, double dt) {
  WorldSettings settings;
  settings.dt = dt;
  settings.gravity = Vec3(0.0, 0.0, -kGravity);
  settings.integrator = integrator;
  settings.contact.sleeping = false;  // a pendulum passes through rest at every turn
  return settings;
}

inline BodyId addBody(World& world, const std::string& name, const Shape& shape, double mass,
                      const Vec3& position, const Quaternion& orientation = Quaternion::identity()) {
  BodyDef def;
  def.name = name;
  def.shape = shape;
  def.mass = mass;
  def.position = position;
  def.orientation = orientation;
  const Expected<BodyId> id = world.createBody(def);
  EXPECT_TRUE(id.ok()) << id.error().message;
  return id.ok() ? id.value() : BodyId{};
}

inline JointId addJoint(World& world, const JointDef& def) {
  const Expected<JointId> id = world.createJoint(def);
  EXPECT_TRUE(id.ok()) << id.error().message;
  return id.ok() ? id.value() : JointId{};
}

inline JointDef hinge(const std::string& name, BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis) {
  JointDef def;
  def.name = name;
  def.type = JointType::Revolute;
  def.bodyA = a;
  def.bodyB = b;
  def.anchor = anchor;
  def.axis = axis;
  return def;
}

inline JointDef slider(const std::string& name, BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis) {
  JointDef def = hinge(name, a, b, anchor, axis);
  def.type = JointType::Prismatic;
  return def;
}

// Why createJoint refused the definition ("" when it made the joint).
inline std::string creationError(World& world, const JointDef& def) {
  const Expected<JointId> made = world.createJoint(def);
  return made.ok() ? "" : made.error().message;
}

// Kinetic plus potential energy (zero height at z = 0), J.
inline double mechanicalEnergy(const World& world) {
  double energy = 0.0;
  for (BodyView body : world.bodies()) {
    if (body.isStatic()) continue;
    energy += body.kineticEnergy() + body.mass() * kGravity * body.position().z();
  }
  return energy;
}

// Times at which samples[k] (taken at times[k]) changes sign, by linear
// interpolation between the two samples around each change.
inline std::vector<double> zeroCrossings(const std::vector<double>& times, const std::vector<double>& samples) {
  std::vector<double> crossings;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const double a = samples[k - 1], b = samples[k];
    if ((a < 0.0 && b >= 0.0) || (a > 0.0 && b <= 0.0))
      crossings.push_back(times[k - 1] + (times[k] - times[k - 1]) * a / (a - b));
  }
  return crossings;
}

// The mean period from crossings that alternate in direction: every second
// crossing is one period on.
inline double meanPeriod(const std::vector<double>& crossings) {
  if (crossings.size() < 3) return NAN;
  const std::size_t periods = (crossings.size() - 1) / 2;
  return (crossings[2 * periods] - crossings[0]) / static_cast<double>(periods);
}

// The period of a physical pendulum released at rest from `amplitude` (rad
// from the vertical): 4 K(sin(amplitude/2)) sqrt(I / (m g d)), I about the
// pivot, d from the pivot to the centre of mass; K the complete elliptic
// integral of the first kind.
inline double physicalPendulumPeriod(double pivotInertia, double mass, double distance, double amplitude) {
  return 4.0 * std::comp_ellint_1(std::sin(0.5 * amplitude)) *
         std::sqrt(pivotInertia / (mass * kGravity * distance));
}

}  // namespace rbsim::testing
