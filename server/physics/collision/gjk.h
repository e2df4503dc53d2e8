#pragma once
// GJK distance between two convex solids (Gilbert, Johnson & Keerthi 1988,
// "A fast procedure for computing the distance between complex objects in
// three-dimensional space"), with the signed-volumes sub-algorithm of
// Montanari, Petrinic & Barbieri 2017 ("Improving the GJK algorithm for
// faster and more reliable distance queries between convex objects", ACM
// TOG 36(3)) to find the closest point of each simplex: it projects onto the
// coordinate plane of largest area instead of solving Johnson's normal
// equations, and so stays reliable for nearly degenerate simplices.

#include "physics/collision/collider.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct GjkSettings {
  int maxIterations = 64;
  // Stop when the distance is known to within tolerance × the larger solid's
  // size (half its bounding-box diagonal): the relative gap of the paper.
  double tolerance = 1e-12;
};

// Which solid GJK sees. Cores: spheres as points, capsules as segments (their
// coreRadius is added back by the caller), everything else unchanged.
enum class GjkShapes { Full, Cores };

struct GjkResult {
  // m: the distance between the two solids (or cores); 0 when they overlap.
  double distance = 0.0;
  // m, world: closest points, pointB − pointA = distance × the unit direction
  // from A to B; from the barycentric coordinates of the final simplex.
  Vec3 pointA = Vec3::Zero();
  Vec3 pointB = Vec3::Zero();
  // The solids overlap or touch (distance within the tolerance of zero):
  // the closest points then only say where, and there is no direction.
  bool overlap = false;
  int iterations = 0;
  bool converged = true;  // false: the iteration cap was hit; the result is the best found
};

GjkResult gjkDistance(const PlacedConvex& a, const PlacedConvex& b,
                      GjkShapes shapes = GjkShapes::Full, const GjkSettings& settings = {});

}  // namespace rbsim
