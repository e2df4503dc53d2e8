#pragma once
// Where two bodies touch, as a manifold of up to
// four points sharing one normal.

#include <array>
#include <cstdint>

#include "rbsim/physics/math_types.h"

namespace rbsim {

struct ContactPoint {
  Vec3 pointA = Vec3::Zero();  // m, world, on A's surface
  Vec3 pointB = Vec3::Zero();  // m, world, on B's surface
  double depth = 0.0;          // m: > 0 penetrating, <= 0 a gap (within the contact margin)
  // Identifies the pair of features that made the point (e.g. a box vertex
  // and a face), stable while they keep touching: the solver matches points
  // across steps by it for warm starting.
  uint32_t featureId = 0;
};

struct ContactManifold {
  Vec3 normal = Vec3::UnitZ();  // unit, world, from A to B; face–vertex: the face's normal,
                                // edge–edge: the cross product of the edges (Baraff's rule)
  std::array<ContactPoint, 4> points{};
  int pointCount = 0;

  void add(const ContactPoint& point) {
    if (pointCount < 4) points[static_cast<std::size_t>(pointCount++)] = point;
  }
};

}  // namespace rbsim
