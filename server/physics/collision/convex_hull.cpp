#include "physics/collision/convex_hull.h"

#include "rbsim/physics/shapes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <utility>

// qhull's headers are C: their macros use C casts and they declare names
// such as `True`; keep both out of every other file.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wpedantic"
extern "C" {
#include <libqhull_r/qhull_ra.h>
}
#pragma GCC diagnostic pop

namespace rbsim {

namespace {

// Relative to the point set's size: below this the set has no volume for
// our purposes (a slab 1e-9 thick on a 1 m body is a polygon).
constexpr double kFlatTolerance = 1e-9;

// Captures whatever qhull writes to its error stream (it never gets stdout:
// outfile is null) and frees qhull's memory on every path out.
class QhullRun {
 public:
  QhullRun() {
    m_errors = open_memstream(&m_buffer, &m_bufferSize);
    qh_zero(&m_qh, m_errors);
  }
  ~QhullRun() {
    int curlong = 0;
    int totlong = 0;
    qh_freeqhull(&m_qh, !qh_ALL);
    qh_memfreeshort(&m_qh, &curlong, &totlong);
    if (m_errors) std::fclose(m_errors);
    std::free(m_buffer);
  }
  QhullRun(const QhullRun&) = delete;
  QhullRun& operator=(const QhullRun&) = delete;

  // Default options: in 3-d qhull merges coplanar facets ('C-0'), so a
  // cube's face comes back as one facet of four vertices.
  int run(std::vector<double>& coordinates) {
    char command[] = "qhull";
    return qh_new_qhull(&m_qh, 3, static_cast<int>(coordinates.size() / 3), coordinates.data(),
                        False, command, nullptr, m_errors);
  }
  qhT* qh() { return &m_qh; }

  // The first line of qhull's error report, e.g. "QH6154 qhull precision
  // error: initial simplex is flat".
  std::string firstErrorLine() {
    if (!m_errors) return "no error text";
    std::fflush(m_errors);
    const std::string text = m_buffer ? std::string(m_buffer, m_bufferSize) : std::string();
    const std::size_t start = text.find("QH");
    const std::string from = start == std::string::npos ? text : text.substr(start);
    const std::string line = from.substr(0, from.find('\n'));
    return line.empty() ? "no error text" : line;
  }

 private:
  qhT m_qh;
  FILE* m_errors = nullptr;
  char* m_buffer = nullptr;
  std::size_t m_bufferSize = 0;
};

// Rejects what qhull cannot build a solid from, with a message a user can act
// on (qhull's own text for these cases is long and cryptic).
Expected<bool> checkVolume(const std::vector<Vec3>& points, const std::string& sourceName) {
  for (const Vec3& p : points) {
    if (!p.allFinite()) return Error{sourceName + ": convex hull input has a non-finite point"};
  }
  std::vector<Vec3> distinct = points;
  const auto lexLess = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(distinct.begin(), distinct.end(), lexLess);
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  if (distinct.size() < 4) {
    return Error{sourceName + ": a convex hull needs at least 4 distinct points, got " +
                 std::to_string(distinct.size())};
  }
  // Affine rank by farthest points: p1 farthest from p0, p2 farthest from the
  // line p0p1, p3 farthest from the plane p0p1p2.
  const Vec3& p0 = distinct[0];
  const auto farthest = [&](auto&& measure) {
    std::size_t best = 0;
    double bestValue = -1.0;
    for (std::size_t i = 0; i < distinct.size(); ++i) {
      const double value = measure(distinct[i]);
      if (value > bestValue) {
        bestValue = value;
        best = i;
      }
    }
    return std::pair{best, bestValue};
  };
  const auto [i1, span] = farthest([&](const Vec3& p) { return (p - p0).norm(); });
  const Vec3 axis = (distinct[i1] - p0) / span;
  const auto [i2, lineDistance] =
      farthest([&](const Vec3& p) { return (p - p0 - (p - p0).dot(axis) * axis).norm(); });
  if (lineDistance <= kFlatTolerance * span) {
    return Error{sourceName + ": the points are collinear, so their convex hull has no volume"};
  }
  const Vec3 normal = axis.cross(distinct[i2] - p0).normalized();
  const auto [i3, planeDistance] =
      farthest([&](const Vec3& p) { return std::abs((p - p0).dot(normal)); });
  (void)i3;
  if (planeDistance <= kFlatTolerance * span) {
    return Error{sourceName + ": the points are coplanar, so their convex hull has no volume"};
  }
  return true;
}

std::vector<vertexT*> facetVertices(const facetT* facet) {
  std::vector<vertexT*> result;
  if (!facet->vertices) return result;
  for (void* const* element = &facet->vertices->e[0].p; *element; ++element) {
    result.push_back(static_cast<vertexT*>(*element));
  }
  return result;
}

// Orders a convex polygon's vertices counter-clockwise seen from outside
// (from the tip of `normal`): increasing angle in the basis (u, normal × u).
void orderCounterClockwise(std::vector<int>& polygon, const std::vector<Vec3>& vertices,
                           const Vec3& normal) {
  Vec3 center = Vec3::Zero();
  for (int v : polygon) center += vertices[static_cast<std::size_t>(v)];
  center /= static_cast<double>(polygon.size());
  Vec3 u = vertices[static_cast<std::size_t>(polygon[0])] - center;
  u = (u - u.dot(normal) * normal).normalized();
  const Vec3 w = normal.cross(u);
  std::vector<std::pair<double, int>> byAngle;
  for (int v : polygon) {
    const Vec3 r = vertices[static_cast<std::size_t>(v)] - center;
    byAngle.emplace_back(std::atan2(r.dot(w), r.dot(u)), v);
  }
  std::sort(byAngle.begin(), byAngle.end());
  for (std::size_t i = 0; i < polygon.size(); ++i) polygon[i] = byAngle[i].second;
}

// The cube map of directions behind supportVertex's starts: a face per
// signed axis, kCubeCells × kCubeCells cells on each.
constexpr int kCubeCells = 4;

int cubeCell(const Vec3& direction) {
  int axis = 0;
  direction.cwiseAbs().maxCoeff(&axis);
  const double major = direction[axis];
  if (!(std::abs(major) > 0.0)) return 0;  // zero or NaN
  const int face = 2 * axis + (major < 0.0 ? 1 : 0);
  const auto bin = [&](double minor) {
    const double t = 0.5 * (minor / std::abs(major) + 1.0);  // [0, 1]
    return std::clamp(static_cast<int>(t * kCubeCells), 0, kCubeCells - 1);
  };
  return (face * kCubeCells + bin(direction[(axis + 1) % 3])) * kCubeCells +
         bin(direction[(axis + 2) % 3]);
}

Vec3 cubeCellCenter(int cell) {
  const int v = cell % kCubeCells;
  const int u = (cell / kCubeCells) % kCubeCells;
  const int face = cell / (kCubeCells * kCubeCells);
  const int axis = face / 2;
  Vec3 direction = Vec3::Zero();
  direction[axis] = face % 2 == 0 ? 1.0 : -1.0;
  direction[(axis + 1) % 3] = (2.0 * (u + 0.5) / kCubeCells) - 1.0;
  direction[(axis + 2) % 3] = (2.0 * (v + 0.5) / kCubeCells) - 1.0;
  return direction;
}

int scanSupport(const std::vector<Vec3>& vertices, const Vec3& direction) {
  int best = 0;
  double bestDot = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const double d = vertices[i].dot(direction);
    if (d > bestDot) {
      bestDot = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

// Steepest ascent of direction · v over the vertex graph: on a convex
// polytope a vertex no neighbour of which is farther is a farthest vertex
// (the polytope lies in the cone of its edges from there).
int climb(const ConvexHull& hull, const Vec3& direction, int start) {
  int current = start;
  double currentDot = direction.dot(hull.vertices[static_cast<std::size_t>(current)]);
  for (;;) {
    int next = -1;
    double nextDot = currentDot;
    const std::size_t v = static_cast<std::size_t>(current);
    for (int k = hull.vertexEdgeStart[v]; k < hull.vertexEdgeStart[v + 1]; ++k) {
      const ConvexHull::FaceEdge& edge = hull.faceEdges[static_cast<std::size_t>(hull.vertexEdges[static_cast<std::size_t>(k)])];
      const int other = edge.start == current ? edge.end : edge.start;
      const double d = direction.dot(hull.vertices[static_cast<std::size_t>(other)]);
      if (d > nextDot) {
        nextDot = d;
        next = other;
      }
    }
    if (next < 0) return current;
    current = next;
    currentDot = nextDot;
  }
}

}  // namespace

Expected<ConvexHull> buildConvexHull(const std::vector<Vec3>& points,
                                     const std::string& sourceName) {
  const auto volume = checkVolume(points, sourceName);
  if (!volume) return volume.error();

  std::vector<double> coordinates;
  coordinates.reserve(points.size() * 3);
  for (const Vec3& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});

  QhullRun run;
  if (run.run(coordinates) != qh_ERRnone) {
    return Error{sourceName + ": convex hull failed (" + run.firstErrorLine() + ")"};
  }
  qhT* qh = run.qh();

  // Hull vertices renumbered in input order, so that the result does not
  // depend on qhull's internal ids.
  std::map<int, int> indexOfInput;
  for (const facetT* facet = qh->facet_list; facet && facet->next; facet = facet->next) {
    for (vertexT* vertex : facetVertices(facet))
      indexOfInput.emplace(qh_pointid(qh, vertex->point), 0);
  }
  ConvexHull hull;
  for (auto& [input, index] : indexOfInput) {
    index = static_cast<int>(hull.vertices.size());
    hull.vertices.push_back(points[static_cast<std::size_t>(input)]);
  }

  std::set<std::array<int, 2>> edges;
  for (const facetT* facet = qh->facet_list; facet && facet->next; facet = facet->next) {
    ConvexHull::Face face;
    for (vertexT* vertex : facetVertices(facet))
      face.vertices.push_back(indexOfInput.at(qh_pointid(qh, vertex->point)));
    if (face.vertices.size() < 3) return Error{sourceName + ": convex hull has a degenerate face"};
    const Vec3 qhullNormal(facet->normal[0], facet->normal[1], facet->normal[2]);
    orderCounterClockwise(face.vertices, hull.vertices, qhullNormal);
    // Newell's normal (the area vector Σ a × b of the ordered polygon, taken
    // about its centre to avoid cancellation far from the origin): exact for
    // a planar polygon, a best fit for a merged, nearly planar one.
    Vec3 center = Vec3::Zero();
    for (int v : face.vertices) center += hull.vertices[static_cast<std::size_t>(v)];
    center /= static_cast<double>(face.vertices.size());
    Vec3 normal = Vec3::Zero();
    for (std::size_t i = 0; i < face.vertices.size(); ++i) {
      const Vec3 a = hull.vertices[static_cast<std::size_t>(face.vertices[i])] - center;
      const Vec3 b =
          hull.vertices[static_cast<std::size_t>(face.vertices[(i + 1) % face.vertices.size()])] -
          center;
      normal += a.cross(b);
    }
    face.normal = normal.normalized();
    if (!face.normal.allFinite() || face.normal.dot(qhullNormal) <= 0.0) {
      return Error{sourceName + ": convex hull has a degenerate face"};
    }
    double offset = 0.0;
    for (int v : face.vertices)
      offset += face.normal.dot(hull.vertices[static_cast<std::size_t>(v)]);
    face.offset = offset / static_cast<double>(face.vertices.size());
    for (std::size_t i = 0; i < face.vertices.size(); ++i) {
      const int a = face.vertices[i];
      const int b = face.vertices[(i + 1) % face.vertices.size()];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
    hull.faces.push_back(std::move(face));
  }
  hull.edges.assign(edges.begin(), edges.end());
  // Faces in a fixed order too: by their smallest vertex, then their normal.
  std::sort(hull.faces.begin(), hull.faces.end(),
            [](const ConvexHull::Face& a, const ConvexHull::Face& b) {
              const int minA = *std::min_element(a.vertices.begin(), a.vertices.end());
              const int minB = *std::min_element(b.vertices.begin(), b.vertices.end());
              if (minA != minB) return minA < minB;
              return std::lexicographical_compare(a.normal.data(), a.normal.data() + 3,
                                                  b.normal.data(), b.normal.data() + 3);
            });
  computeHullTopology(hull);
  return hull;
}

void computeHullTopology(ConvexHull& hull) {
  // Pairing the directed edges of the face loops finds each edge with both
  // its faces; sorted by (min, max) vertex, then face.
  struct Directed {
    int low, high, start, end, face;
  };
  std::vector<Directed> directed;
  for (std::size_t f = 0; f < hull.faces.size(); ++f) {
    const std::vector<int>& loop = hull.faces[f].vertices;
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const int a = loop[k];
      const int b = loop[(k + 1) % loop.size()];
      directed.push_back({std::min(a, b), std::max(a, b), a, b, static_cast<int>(f)});
    }
  }
  std::sort(directed.begin(), directed.end(), [](const Directed& x, const Directed& y) {
    if (x.low != y.low) return x.low < y.low;
    if (x.high != y.high) return x.high < y.high;
    return x.face < y.face;
  });
  hull.faceEdges.clear();
  hull.faceEdges.reserve(directed.size() / 2);
  for (std::size_t i = 0; i + 1 < directed.size();) {
    const Directed& x = directed[i];
    const Directed& y = directed[i + 1];
    if (x.low == y.low && x.high == y.high) {
      hull.faceEdges.push_back({x.start, x.end, x.face, y.face});
      i += 2;
    } else {
      ++i;  // an edge without its twin (a malformed hull): no axis from it
    }
  }

  const std::size_t vertexCount = hull.vertices.size();
  hull.vertexEdgeStart.assign(vertexCount + 1, 0);
  for (const ConvexHull::FaceEdge& edge : hull.faceEdges) {
    ++hull.vertexEdgeStart[static_cast<std::size_t>(edge.start) + 1];
    ++hull.vertexEdgeStart[static_cast<std::size_t>(edge.end) + 1];
  }
  for (std::size_t v = 0; v < vertexCount; ++v)
    hull.vertexEdgeStart[v + 1] += hull.vertexEdgeStart[v];
  hull.vertexEdges.assign(static_cast<std::size_t>(hull.vertexEdgeStart[vertexCount]), 0);
  std::vector<int> fill(hull.vertexEdgeStart.begin(), hull.vertexEdgeStart.end() - 1);
  for (std::size_t e = 0; e < hull.faceEdges.size(); ++e) {
    const ConvexHull::FaceEdge& edge = hull.faceEdges[e];
    hull.vertexEdges[static_cast<std::size_t>(fill[static_cast<std::size_t>(edge.start)]++)] = static_cast<int>(e);
    hull.vertexEdges[static_cast<std::size_t>(fill[static_cast<std::size_t>(edge.end)]++)] = static_cast<int>(e);
  }

  hull.faceNormals.clear();
  hull.faceOffsets.clear();
  for (const ConvexHull::Face& face : hull.faces) {
    hull.faceNormals.push_back(face.normal);
    hull.faceOffsets.push_back(face.offset);
  }
  hull.centroid = Vec3::Zero();
  for (const Vec3& v : hull.vertices) hull.centroid += v;
  if (vertexCount > 0) hull.centroid /= static_cast<double>(vertexCount);
  double radius2 = 0.0;
  hull.lowerCorner = Vec3::Constant(std::numeric_limits<double>::infinity());
  hull.upperCorner = -hull.lowerCorner;
  for (const Vec3& v : hull.vertices) {
    radius2 = std::max(radius2, (v - hull.centroid).squaredNorm());
    hull.lowerCorner = hull.lowerCorner.cwiseMin(v);
    hull.upperCorner = hull.upperCorner.cwiseMax(v);
  }
  hull.radius = std::sqrt(radius2);

  hull.supportStarts.clear();
  if (vertexCount > kWalkedSupportVertices) {
    for (int cell = 0; cell < 6 * kCubeCells * kCubeCells; ++cell)
      hull.supportStarts.push_back(scanSupport(hull.vertices, cubeCellCenter(cell)));
  }
}

int supportVertex(const ConvexHull& hull, const Vec3& direction) {
  if (hull.supportStarts.empty()) return scanSupport(hull.vertices, direction);
  return climb(hull, direction, hull.supportStarts[static_cast<std::size_t>(cubeCell(direction))]);
}

int lowestVertexFrom(const ConvexHull& hull, const Vec3& direction, int start) {
  return climb(hull, -direction, start);
}

}  // namespace rbsim

namespace rbsim {

namespace {

// How far `point` lies outside the hull: the largest distance above its
// face planes (negative inside).
double distanceOutside(const ConvexHull& hull, const Vec3& point) {
  double outside = -std::numeric_limits<double>::infinity();
  for (const ConvexHull::Face& face : hull.faces)
    outside = std::max(outside, face.normal.dot(point) - face.offset);
  return outside;
}

TriangleMesh fanTriangulation(const ConvexHull& hull) {
  TriangleMesh mesh;
  mesh.vertices = hull.vertices;
  // Each face is convex and counter-clockwise seen from outside: a fan.
  for (const ConvexHull::Face& face : hull.faces)
    for (std::size_t k = 1; k + 1 < face.vertices.size(); ++k)
      mesh.triangles.push_back({face.vertices[0], face.vertices[k], face.vertices[k + 1]});
  return mesh;
}

}  // namespace

Expected<TriangleMesh> convexHullMesh(const std::vector<Vec3>& points, const std::string& sourceName) {
  Expected<ConvexHull> hull = buildConvexHull(points, sourceName);
  if (!hull) return hull.error();
  return fanTriangulation(*hull);
}

Expected<SimplifiedHullMesh> simplifiedConvexHullMesh(const std::vector<Vec3>& points,
                                                      std::size_t maxVertices, double tolerance,
                                                      const std::string& sourceName) {
  if (!(std::isfinite(tolerance) && tolerance >= 0.0))
    return Error{sourceName + ": the hull tolerance must be finite and not negative"};
  if (maxVertices < 4) return Error{sourceName + ": a hull needs at least 4 vertices"};
  Expected<ConvexHull> full = buildConvexHull(points, sourceName);
  if (!full) return full.error();
  SimplifiedHullMesh result;
  result.fullVertexCount = full->vertices.size();
  const std::vector<Vec3>& candidates = full->vertices;

  // Start from the extreme vertices along the axes and the diagonals, in a
  // fixed order, so that the result depends on the points alone.
  std::vector<char> chosen(candidates.size(), 0);
  std::vector<Vec3> subset;
  const auto choose = [&](std::size_t i) {
    if (chosen[i]) return;
    chosen[i] = 1;
    subset.push_back(candidates[i]);
  };
  for (const Vec3& direction :
       {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1),
        Vec3(0, 0, -1), Vec3(1, 1, 1), Vec3(-1, -1, -1), Vec3(1, -1, 1), Vec3(-1, 1, -1)}) {
    if (subset.size() >= maxVertices) break;
    choose(static_cast<std::size_t>(scanSupport(candidates, direction)));
  }
  for (;;) {
    Expected<ConvexHull> hull = buildConvexHull(subset, sourceName);
    if (!hull) {
      // The extremes can be coplanar (a thin plate): the full hull stands.
      result.mesh = fanTriangulation(*full);
      return result;
    }
    // Each round adds the farthest vertices outside, up to a quarter as
    // many as the hull has (one qhull run per round, not per vertex).
    std::vector<std::pair<double, std::size_t>> outsiders;
    double outside = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      if (chosen[i]) continue;
      const double d = distanceOutside(*hull, candidates[i]);
      outside = std::max(outside, d);
      if (d > tolerance) outsiders.emplace_back(-d, i);  // farthest first, then by index
    }
    result.outside = std::max(0.0, outside);
    if (outsiders.empty() || hull->vertices.size() >= maxVertices) {
      result.mesh = fanTriangulation(*hull);
      return result;
    }
    const std::size_t room = maxVertices - std::min(maxVertices, subset.size());
    const std::size_t batch =
        std::min({outsiders.size(), std::max<std::size_t>(1, subset.size() / 4), std::max<std::size_t>(1, room)});
    std::partial_sort(outsiders.begin(), outsiders.begin() + static_cast<std::ptrdiff_t>(batch),
                      outsiders.end());
    for (std::size_t k = 0; k < batch; ++k) choose(outsiders[k].second);
  }
}

}  // namespace rbsim
