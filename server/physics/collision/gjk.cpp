#include "physics/collision/gjk.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace rbsim {

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
// A triangle whose area is below this fraction of its longest edge squared,
// or a tetrahedron whose volume is below it times the edge cubed, is treated
// as its faces: its plane (or its inside test) is numerically meaningless.
constexpr double kFlatRatio = 1e-12;

// A vertex of the Minkowski difference A − B with the support points that
// made it, so that barycentric coordinates give the closest points.
struct SimplexVertex {
  Vec3 w = Vec3::Zero();  // a − b
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::Zero();
};

struct Simplex {
  std::array<SimplexVertex, 4> vertex;
  std::array<double, 4> lambda{};
  int size = 0;
};

// A face of the simplex (by vertex index) and the barycentric coordinates of
// its point closest to the origin.
struct SubSimplex {
  std::array<int, 4> index{};
  std::array<double, 4> lambda{};
  int size = 0;

  Vec3 point(const std::array<Vec3, 4>& w) const {
    Vec3 p = Vec3::Zero();
    for (int i = 0; i < size; ++i)
      p += lambda[static_cast<std::size_t>(i)] *
           w[static_cast<std::size_t>(index[static_cast<std::size_t>(i)])];
    return p;
  }
};

// The paper's compareSigns: true only for two strictly positive or two
// strictly negative values, so a zero sub-volume sends us to the faces.
bool sameSign(double a, double b) {
  return (a > 0.0 && b > 0.0) || (a < 0.0 && b < 0.0);
}

SubSimplex single(int i) {
  return {{i, 0, 0, 0}, {1.0, 0.0, 0.0, 0.0}, 1};
}

// Picks the candidate closest to the origin; the first offered wins ties,
// which keeps the choice deterministic.
struct Closest {
  const std::array<Vec3, 4>& w;
  SubSimplex best{};
  double bestDistance2 = std::numeric_limits<double>::infinity();
  void offer(const SubSimplex& candidate) {
    const double d2 = candidate.point(w).squaredNorm();
    if (best.size == 0 || d2 < bestDistance2) {  // never leave it empty, even on NaN
      bestDistance2 = d2;
      best = candidate;
    }
  }
};

// Segment (S1D of the paper): project the origin onto the line, then read
// the barycentric coordinates off the axis along which the segment is longest.
SubSimplex closestOnSegment(const std::array<Vec3, 4>& w, int i, int j) {
  const Vec3& a = w[static_cast<std::size_t>(i)];
  const Vec3& b = w[static_cast<std::size_t>(j)];
  const Vec3 t = b - a;
  const double tt = t.squaredNorm();
  const double size = std::max(a.norm(), b.norm());
  if (!(tt > (kEpsilon * size) * (kEpsilon * size)))
    return a.squaredNorm() <= b.squaredNorm() ? single(i) : single(j);
  const Vec3 p = a - (a.dot(t) / tt) * t;
  int axis = 0;
  t.cwiseAbs().maxCoeff(&axis);
  const double mu = a[axis] - b[axis];
  const double ca = p[axis] - b[axis];  // λa · mu
  const double cb = a[axis] - p[axis];  // λb · mu
  if (sameSign(mu, ca) && sameSign(mu, cb)) return {{i, j, 0, 0}, {ca / mu, cb / mu, 0.0, 0.0}, 2};
  // Outside: λb <= 0 puts the projection beyond a, λa <= 0 beyond b.
  return sameSign(mu, cb) ? single(j) : single(i);
}

// Signed area ×2 of (p, q, r) projected onto the coordinate plane (k, l).
double area2(const Vec3& p, const Vec3& q, const Vec3& r, int k, int l) {
  return (q[k] - p[k]) * (r[l] - p[l]) - (r[k] - p[k]) * (q[l] - p[l]);
}

// Triangle (S2D): project the origin onto the plane, then solve for the
// barycentric coordinates in the coordinate plane where the triangle's
// projection has the largest area (its normal's largest component).
SubSimplex closestOnTriangle(const std::array<Vec3, 4>& w, int i, int j, int k) {
  const std::array<int, 3> ids = {i, j, k};
  const Vec3& a = w[static_cast<std::size_t>(i)];
  const Vec3& b = w[static_cast<std::size_t>(j)];
  const Vec3& c = w[static_cast<std::size_t>(k)];
  const Vec3 n = (b - a).cross(c - a);
  const double longest2 =
      std::max({(b - a).squaredNorm(), (c - a).squaredNorm(), (c - b).squaredNorm()});
  const double nn = n.squaredNorm();
  std::array<double, 3> cofactor{};
  double mu = 0.0;
  if (nn > (kFlatRatio * longest2) * (kFlatRatio * longest2)) {
    const Vec3 p = n * (a.dot(n) / nn);
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    const int u = (axis + 1) % 3;
    const int v = (axis + 2) % 3;
    mu = n[axis];  // = area2(a, b, c) in (u, v)
    cofactor = {area2(p, b, c, u, v), area2(a, p, c, u, v), area2(a, b, p, u, v)};
    if (sameSign(mu, cofactor[0]) && sameSign(mu, cofactor[1]) && sameSign(mu, cofactor[2])) {
      return {{i, j, k, 0}, {cofactor[0] / mu, cofactor[1] / mu, cofactor[2] / mu, 0.0}, 3};
    }
  }
  // Outside (or a sliver): the closest point is on an edge whose opposite
  // vertex has a non-positive coordinate; a sliver tries all three.
  Closest closest{w};
  for (int m = 0; m < 3; ++m) {
    if (sameSign(mu, cofactor[static_cast<std::size_t>(m)])) continue;
    closest.offer(closestOnSegment(w, ids[static_cast<std::size_t>((m + 1) % 3)],
                                   ids[static_cast<std::size_t>((m + 2) % 3)]));
  }
  return closest.best;
}

double det3(const Vec3& x, const Vec3& y, const Vec3& z) {
  return x.dot(y.cross(z));
}

// Tetrahedron (S3D): the cofactors of [w0 w1 w2 w3; 1 1 1 1] along its last
// row are the signed volumes whose ratios are the origin's barycentric
// coordinates (Cramer's rule); all of the determinant's sign means inside.
SubSimplex closestOnTetrahedron(const std::array<Vec3, 4>& w) {
  const std::array<double, 4> cofactor = {-det3(w[1], w[2], w[3]), det3(w[0], w[2], w[3]),
                                          -det3(w[0], w[1], w[3]), det3(w[0], w[1], w[2])};
  const double detM = cofactor[0] + cofactor[1] + cofactor[2] + cofactor[3];
  double longest = 0.0;
  for (int p = 0; p < 4; ++p)
    for (int q = p + 1; q < 4; ++q)
      longest = std::max(longest,
                         (w[static_cast<std::size_t>(p)] - w[static_cast<std::size_t>(q)]).norm());
  const bool flat = !(std::abs(detM) > kFlatRatio * longest * longest * longest);
  if (!flat && sameSign(detM, cofactor[0]) && sameSign(detM, cofactor[1]) &&
      sameSign(detM, cofactor[2]) && sameSign(detM, cofactor[3])) {
    return {{0, 1, 2, 3},
            {cofactor[0] / detM, cofactor[1] / detM, cofactor[2] / detM, cofactor[3] / detM},
            4};
  }
  Closest closest{w};
  for (int m = 0; m < 4; ++m) {
    if (!flat && sameSign(detM, cofactor[static_cast<std::size_t>(m)])) continue;
    std::array<int, 3> face{};
    for (int q = 0, f = 0; q < 4; ++q)
      if (q != m) face[static_cast<std::size_t>(f++)] = q;
    closest.offer(closestOnTriangle(w, face[0], face[1], face[2]));
  }
  return closest.best;
}

// Reduces the simplex to the smallest face holding its point closest to the
// origin and returns that point.
Vec3 reduceToClosest(Simplex& simplex) {
  std::array<Vec3, 4> w;
  for (int i = 0; i < simplex.size; ++i)
    w[static_cast<std::size_t>(i)] = simplex.vertex[static_cast<std::size_t>(i)].w;
  SubSimplex sub;
  switch (simplex.size) {
    case 1:
      sub = single(0);
      break;
    case 2:
      sub = closestOnSegment(w, 0, 1);
      break;
    case 3:
      sub = closestOnTriangle(w, 0, 1, 2);
      break;
    default:
      sub = closestOnTetrahedron(w);
      break;
  }
  Simplex reduced;
  reduced.size = sub.size;
  for (int i = 0; i < sub.size; ++i) {
    const auto slot = static_cast<std::size_t>(i);
    reduced.vertex[slot] = simplex.vertex[static_cast<std::size_t>(sub.index[slot])];
    reduced.lambda[slot] = sub.lambda[slot];
  }
  simplex = reduced;
  return sub.point(w);
}

template <class SupportA, class SupportB>
GjkResult runGjk(const SupportA& supportA, const SupportB& supportB, const Vec3& initialDirection,
                 double absoluteTolerance, int maxIterations) {
  // The support of A − B along −v: the point of A − B that GJK adds next.
  const auto support = [&](const Vec3& v) {
    SimplexVertex s;
    s.a = supportA(-v);
    s.b = supportB(v);
    s.w = s.a - s.b;
    return s;
  };
  Simplex simplex;
  simplex.vertex[0] = support(initialDirection.allFinite() && initialDirection.squaredNorm() > 0.0
                                  ? initialDirection
                                  : Vec3::UnitX());
  simplex.lambda[0] = 1.0;
  simplex.size = 1;
  Vec3 v = simplex.vertex[0].w;

  GjkResult result;
  result.converged = false;
  double largestVertex = v.norm();
  for (int iteration = 0; iteration < maxIterations; ++iteration) {
    result.iterations = iteration + 1;
    const double vv = v.squaredNorm();
    // Origin on the simplex, to within its own rounding (Montanari's
    // second criterion) or to within the distance tolerance.
    if (!(vv > std::max(absoluteTolerance * absoluteTolerance,
                        (64 * kEpsilon * largestVertex) * (64 * kEpsilon * largestVertex)))) {
      result.overlap = true;
      result.converged = true;
      break;
    }
    const SimplexVertex next = support(v);
    if (!next.w.allFinite()) break;
    largestVertex = std::max(largestVertex, next.w.norm());
    // ‖v‖ is an upper bound of the distance and v·w/‖v‖ a lower bound: stop
    // when they agree to within the tolerance.
    const double gap = vv - v.dot(next.w);
    if (gap <= absoluteTolerance * std::sqrt(vv)) {
      result.converged = true;
      break;
    }
    // A support point already in the simplex cannot make progress: we are at
    // the limit of the arithmetic.
    bool repeated = false;
    for (int i = 0; i < simplex.size; ++i) {
      repeated =
          repeated || (next.w - simplex.vertex[static_cast<std::size_t>(i)].w).squaredNorm() <=
                          (kEpsilon * largestVertex) * (kEpsilon * largestVertex);
    }
    if (repeated) {
      result.converged = true;
      break;
    }
    Simplex trial = simplex;
    trial.vertex[static_cast<std::size_t>(trial.size++)] = next;
    const Vec3 closest = reduceToClosest(trial);
    if (trial.size == 4) {  // the origin is inside the tetrahedron
      simplex = trial;
      v = Vec3::Zero();
      result.overlap = true;
      result.converged = true;
      break;
    }
    // ‖v‖ must shrink strictly; if rounding stops it, keep the better simplex.
    if (!(closest.squaredNorm() < vv)) {
      result.converged = true;
      break;
    }
    simplex = trial;
    v = closest;
  }

  result.pointA = Vec3::Zero();
  result.pointB = Vec3::Zero();
  for (int i = 0; i < simplex.size; ++i) {
    const auto slot = static_cast<std::size_t>(i);
    result.pointA += simplex.lambda[slot] * simplex.vertex[slot].a;
    result.pointB += simplex.lambda[slot] * simplex.vertex[slot].b;
  }
  result.distance = result.overlap ? 0.0 : v.norm();
  return result;
}

}  // namespace

GjkResult gjkDistance(const PlacedConvex& a, const PlacedConvex& b, GjkShapes shapes,
                      const GjkSettings& settings) {
  const bool cores = shapes == GjkShapes::Cores;
  const auto supportOf = [cores](const PlacedConvex& shape) {
    return [&shape, cores](const Vec3& direction) -> Vec3 {
      const Vec3 local = shape.pose.inverseRotate(direction);
      return shape.pose.apply(cores ? coreSupportPoint(*shape.geometry, local)
                                    : supportPoint(*shape.geometry, local));
    };
  };
  const double sizeA = geometrySize(*a.geometry);
  const double sizeB = geometrySize(*b.geometry);
  // Relative to the solids' size, with a floor at the rounding of world
  // coordinates far from the origin.
  const double magnitude = a.pose.translation.norm() + b.pose.translation.norm() + sizeA + sizeB;
  const double tolerance =
      std::max(settings.tolerance * std::max(sizeA, sizeB), 16 * kEpsilon * magnitude);
  const Vec3 initial =
      a.pose.apply(interiorPoint(*a.geometry)) - b.pose.apply(interiorPoint(*b.geometry));
  return runGjk(supportOf(a), supportOf(b), initial, tolerance, settings.maxIterations);
}

}  // namespace rbsim
