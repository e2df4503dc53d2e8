#include <numbers>

#include "rbsim/physics/mass_properties.h"

namespace rbsim {
namespace {

constexpr double kPi = std::numbers::pi;

MassProperties diagonalBody(double volume, double density, const Vec3& inertiaDiagonal) {
  MassProperties props;
  props.volume = volume;
  props.mass = density * volume;
  props.inertia = inertiaDiagonal.asDiagonal();
  return props;
}

}  // namespace

MassProperties sphereMassProperties(double radius, double density) {
  const double volume = 4.0 / 3.0 * kPi * radius * radius * radius;
  const double moment = 0.4 * density * volume * radius * radius;  // (2/5) m r²
  return diagonalBody(volume, density, Vec3::Constant(moment));
}

MassProperties boxMassProperties(const Vec3& halfExtents, double density) {
  const Vec3 side = 2.0 * halfExtents;
  const double volume = side.prod();
  const double mass = density * volume;
  // (m/12)(b² + c²) and cyclic, with b, c the full side lengths.
  const Vec3 sq = side.cwiseProduct(side);
  return diagonalBody(volume, density,
                      mass / 12.0 * Vec3(sq.y() + sq.z(), sq.z() + sq.x(), sq.x() + sq.y()));
}

MassProperties cylinderMassProperties(double radius, double halfLength, double density) {
  const double r2 = radius * radius;
  const double volume = kPi * r2 * 2.0 * halfLength;
  const double mass = density * volume;
  // About the axis m r²/2; across it m (3 r² + L²)/12 with L = 2·halfLength.
  const double transverse = mass * (r2 / 4.0 + halfLength * halfLength / 3.0);
  return diagonalBody(volume, density, Vec3(transverse, transverse, 0.5 * mass * r2));
}

MassProperties capsuleMassProperties(double radius, double halfLength, double density) {
  const double r2 = radius * radius;
  const double h = halfLength;
  const double cylinderVolume = kPi * r2 * 2.0 * h;
  const double hemisphereVolume = 2.0 / 3.0 * kPi * r2 * radius;
  const double cylinderMass = density * cylinderVolume;
  const double hemisphereMass = density * hemisphereVolume;

  // Each cap is half a sphere, so about its own flat face it has half of a
  // sphere's moments: (2/5) m_h r² about any axis through the face centre.
  // Its centroid sits 3r/8 above the face, so about an axis through the
  // centroid the transverse moment is m_h (2/5 r² − (3r/8)²), and shifted to
  // the capsule centre (distance h + 3r/8) it becomes
  // m_h (2/5 r² − 9/64 r² + (h + 3r/8)²) = m_h (2/5 r² + h² + 3 h r/4).
  const double capTransverse = hemisphereMass * (0.4 * r2 + h * h + 0.75 * h * radius);
  const double capAxial = 0.4 * hemisphereMass * r2;

  const double transverse = cylinderMass * (r2 / 4.0 + h * h / 3.0) + 2.0 * capTransverse;
  const double axial = 0.5 * cylinderMass * r2 + 2.0 * capAxial;
  return diagonalBody(cylinderVolume + 2.0 * hemisphereVolume, density,
                      Vec3(transverse, transverse, axial));
}

}  // namespace rbsim
