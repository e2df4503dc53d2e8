#include "rbsim/physics/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace rbsim {
namespace {

// A triangle whose doubled area |(b − a) × (c − a)| is below this fraction of
// the squared bounding-box diagonal counts as having zero area. Collinear
// vertices give a cross product of round-off size (~1e-16 of the diagonal²);
// real sliver triangles of a 2-million-triangle mesh are still ~1e-7 of it.
constexpr double kDegenerateAreaFraction = 1e-12;

// The enclosed volume must exceed this fraction of the bounding box's volume
// scale (diagonal³); below it the mesh is flat (e.g. a tetrahedron squashed
// into a plane) and has no well-defined inertia.
constexpr double kZeroVolumeFraction = 1e-12;

// One triangle's traversal of an edge, keyed by the edge's unordered vertex
// pair so that sorting brings the two sides of every edge together.
struct HalfEdge {
  int low = 0;
  int high = 0;
  int from = 0;  // the triangle traverses from -> (the other vertex)
  int triangle = 0;
};

std::string prefix(const std::string& sourceName) {
  return sourceName + ": ";
}

}  // namespace

Expected<bool> validateClosedMesh(const TriangleMesh& mesh, const std::string& sourceName) {
  const int vertexCount = static_cast<int>(mesh.vertices.size());
  const int triangleCount = static_cast<int>(mesh.triangles.size());
  if (triangleCount == 0) return Error{prefix(sourceName) + "mesh has no triangles"};

  // Indices first: everything below dereferences them.
  for (int t = 0; t < triangleCount; ++t) {
    const auto& tri = mesh.triangles[static_cast<size_t>(t)];
    for (int index : tri) {
      if (index < 0 || index >= vertexCount) {
        std::ostringstream message;
        message << prefix(sourceName) << "triangle " << t << " has vertex index " << index
                << " out of range (" << vertexCount << " vertices)";
        return Error{message.str()};
      }
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      std::ostringstream message;
      message << prefix(sourceName) << "triangle " << t << " is degenerate: it repeats a vertex ("
              << tri[0] << ", " << tri[1] << ", " << tri[2] << ")";
      return Error{message.str()};
    }
  }

  // Size of the referenced part of the mesh (unreferenced vertices must not
  // set the scale of the tolerances).
  Vec3 lower = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 upper = -lower;
  for (const auto& tri : mesh.triangles) {
    for (int index : tri) {
      const Vec3& p = mesh.vertices[static_cast<size_t>(index)];
      if (!p.allFinite()) {
        std::ostringstream message;
        message << prefix(sourceName) << "vertex " << index << " has a non-finite coordinate";
        return Error{message.str()};
      }
      lower = lower.cwiseMin(p);
      upper = upper.cwiseMax(p);
    }
  }
  const double diagonal = (upper - lower).norm();
  // Measuring from the box centre keeps the signed-volume sum accurate for a
  // mesh far from the origin (the terms are then of the mesh's own size).
  const Vec3 center = 0.5 * (lower + upper);

  double sixVolume = 0.0;
  for (int t = 0; t < triangleCount; ++t) {
    const auto& tri = mesh.triangles[static_cast<size_t>(t)];
    const Vec3 a = mesh.vertices[static_cast<size_t>(tri[0])] - center;
    const Vec3 b = mesh.vertices[static_cast<size_t>(tri[1])] - center;
    const Vec3 c = mesh.vertices[static_cast<size_t>(tri[2])] - center;
    const Vec3 doubleAreaNormal = (b - a).cross(c - a);
    if (!(doubleAreaNormal.norm() > kDegenerateAreaFraction * diagonal * diagonal)) {
      std::ostringstream message;
      message << prefix(sourceName) << "triangle " << t << " is degenerate: zero area (vertices "
              << tri[0] << ", " << tri[1] << ", " << tri[2] << " are collinear)";
      return Error{message.str()};
    }
    sixVolume += a.dot(b.cross(c));
  }

  // Closed and consistently wound <=> every undirected edge has exactly two
  // half-edges and they run in opposite directions. Sorting (rather than a
  // hash map) keeps the reported "first problem" deterministic.
  std::vector<HalfEdge> halfEdges;
  halfEdges.reserve(3 * mesh.triangles.size());
  for (int t = 0; t < triangleCount; ++t) {
    const auto& tri = mesh.triangles[static_cast<size_t>(t)];
    for (int k = 0; k < 3; ++k) {
      const int from = tri[static_cast<size_t>(k)];
      const int to = tri[static_cast<size_t>((k + 1) % 3)];
      halfEdges.push_back({std::min(from, to), std::max(from, to), from, t});
    }
  }
  std::sort(halfEdges.begin(), halfEdges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    if (x.low != y.low) return x.low < y.low;
    if (x.high != y.high) return x.high < y.high;
    return x.triangle < y.triangle;
  });
  for (size_t begin = 0; begin < halfEdges.size();) {
    size_t end = begin + 1;
    while (end < halfEdges.size() && halfEdges[end].low == halfEdges[begin].low &&
           halfEdges[end].high == halfEdges[begin].high) {
      ++end;
    }
    const HalfEdge& first = halfEdges[begin];
    const size_t uses = end - begin;
    if (uses == 1) {
      std::ostringstream message;
      message << prefix(sourceName) << "mesh is open: edge (" << first.low << ", " << first.high
              << ") belongs to only one triangle (triangle " << first.triangle << ")";
      return Error{message.str()};
    }
    if (uses > 2) {
      std::ostringstream message;
      message << prefix(sourceName) << "mesh is not manifold: edge (" << first.low << ", "
              << first.high << ") is shared by " << uses << " triangles (";
      for (size_t i = begin; i < end; ++i) {
        message << (i == begin ? "" : ", ") << halfEdges[i].triangle;
      }
      message << ")";
      return Error{message.str()};
    }
    const HalfEdge& second = halfEdges[begin + 1];
    if (first.from == second.from) {
      const int to = first.from == first.low ? first.high : first.low;
      std::ostringstream message;
      message << prefix(sourceName) << "inconsistent winding: triangles " << first.triangle
              << " and " << second.triangle << " both traverse edge " << first.from << " -> " << to
              << " in the same direction";
      return Error{message.str()};
    }
    begin = end;
  }

  // With consistent winding the signed volume is ± the enclosed volume; its
  // sign tells outward (counter-clockwise seen from outside) from inward.
  const double volume = sixVolume / 6.0;
  const double volumeTolerance = kZeroVolumeFraction * diagonal * diagonal * diagonal;
  if (std::abs(volume) <= volumeTolerance) {
    std::ostringstream message;
    message << prefix(sourceName) << "mesh encloses no volume (" << volume << " m^3): it is flat";
    return Error{message.str()};
  }
  if (volume < 0.0) {
    std::ostringstream message;
    message << prefix(sourceName)
            << "the winding is inverted (triangles are clockwise seen from outside, normals "
               "point inward): the enclosed volume comes out as "
            << volume << " m^3";
    return Error{message.str()};
  }
  return true;
}

Expected<bool> validateSurfaceMesh(const TriangleMesh& mesh, const std::string& sourceName) {
  const int vertexCount = static_cast<int>(mesh.vertices.size());
  const int triangleCount = static_cast<int>(mesh.triangles.size());
  if (triangleCount == 0) return Error{prefix(sourceName) + "mesh has no triangles"};
  for (int t = 0; t < triangleCount; ++t) {
    for (int index : mesh.triangles[static_cast<size_t>(t)]) {
      if (index < 0 || index >= vertexCount) {
        std::ostringstream message;
        message << prefix(sourceName) << "triangle " << t << " has vertex index " << index
                << " out of range (" << vertexCount << " vertices)";
        return Error{message.str()};
      }
      if (!mesh.vertices[static_cast<size_t>(index)].allFinite()) {
        std::ostringstream message;
        message << prefix(sourceName) << "triangle " << t << ": vertex " << index
                << " has a non-finite coordinate";
        return Error{message.str()};
      }
    }
  }
  Vec3 lower, upper;
  usedVertexBounds(mesh, lower, upper);
  const double minimumDoubledArea = kDegenerateAreaFraction * (upper - lower).squaredNorm();
  for (int t = 0; t < triangleCount; ++t) {
    const auto& tri = mesh.triangles[static_cast<size_t>(t)];
    const Vec3& a = mesh.vertices[static_cast<size_t>(tri[0])];
    const Vec3& b = mesh.vertices[static_cast<size_t>(tri[1])];
    const Vec3& c = mesh.vertices[static_cast<size_t>(tri[2])];
    if (!((b - a).cross(c - a).norm() > minimumDoubledArea)) {
      std::ostringstream message;
      message << prefix(sourceName) << "triangle " << t << " (vertices " << tri[0] << ", "
              << tri[1] << ", " << tri[2] << ") is degenerate: it has zero area";
      return Error{message.str()};
    }
  }
  return true;
}

TriangleMesh transformed(const TriangleMesh& mesh, const Mat3& rotation, const Vec3& translation) {
  TriangleMesh result;
  result.triangles = mesh.triangles;
  result.vertices.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) result.vertices.push_back(rotation * p + translation);
  return result;
}

void usedVertexBounds(const TriangleMesh& mesh, Vec3& lower, Vec3& upper) {
  lower = Vec3::Constant(std::numeric_limits<double>::infinity());
  upper = -lower;
  for (const auto& triangle : mesh.triangles) {
    for (int index : triangle) {
      lower = lower.cwiseMin(mesh.vertices[static_cast<std::size_t>(index)]);
      upper = upper.cwiseMax(mesh.vertices[static_cast<std::size_t>(index)]);
    }
  }
}

}  // namespace rbsim
