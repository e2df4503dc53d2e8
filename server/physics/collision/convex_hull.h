#pragma once
// A convex polyhedron with its faces and edges: the collision geometry of a
// mesh (the hull of its vertices), built with qhull.

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "rbsim/physics/expected.h"
#include "rbsim/physics/math_types.h"

namespace rbsim {

struct ConvexHull {
  struct Face {
    Vec3 normal = Vec3::UnitZ();  // unit, outward
    double offset = 0.0;          // m: normal · p = offset on the face
    std::vector<int> vertices;    // counter-clockwise seen from outside; coplanar triangles merged
  };
  // An edge with its two faces: face0 runs start -> end in its
  // counter-clockwise loop, face1 runs end -> start. On the Gauss map
  // (the unit sphere of face normals) it is the arc from face0's normal to
  // face1's.
  struct FaceEdge {
    int start = 0;
    int end = 0;
    int face0 = 0;
    int face1 = 0;
  };
  std::vector<Vec3> vertices;                // m, in the hull's frame; only hull vertices
  std::vector<Face> faces;
  std::vector<std::array<int, 2>> edges;     // each undirected edge once, for SAT edge axes

  // Derived by computeHullTopology() when the hull is made, so that a
  // collision query never rebuilds them. The narrow phase needs them; a
  // hull without them (faceEdges empty) is not a valid collision hull.
  std::vector<FaceEdge> faceEdges;  // sorted by (min, max) vertex index
  // Per vertex, the faceEdges that meet there: vertexEdges[vertexEdgeStart[v]
  // .. vertexEdgeStart[v + 1]) (compressed rows).
  std::vector<int> vertexEdgeStart;
  std::vector<int> vertexEdges;
  std::vector<Vec3> faceNormals;    // faces[f].normal, contiguous for the face queries
  std::vector<double> faceOffsets;  // faces[f].offset
  Vec3 centroid = Vec3::Zero();     // mean of the vertices: a point strictly inside
  double radius = 0.0;              // m: the farthest vertex from the centroid
  Vec3 lowerCorner = Vec3::Zero();  // m: the vertices' bounding box
  Vec3 upperCorner = Vec3::Zero();
  // For hulls of more than kWalkedSupportVertices vertices: the support
  // vertex of each cell of a cube map of directions, where a hill climb over
  // the vertex graph starts (supportVertex); empty for small hulls.
  std::vector<int> supportStarts;
};

// Hulls with more vertices than this find support points by hill climbing
// over their vertex graph from a precomputed start; smaller ones scan.
inline constexpr std::size_t kWalkedSupportVertices = 32;

// Fills the derived members of a hull whose vertices and faces are set.
void computeHullTopology(ConvexHull& hull);

// The index of a vertex farthest along `direction` (any length; zero or NaN
// gives some vertex). A linear scan on small hulls (the first farthest
// vertex); on larger ones a climb over the vertex graph, which on a convex
// polytope ends at a farthest vertex (a vertex no neighbour of which is
// farther is farthest), started from the cube-map cell of the direction, so
// the answer depends on the direction alone.
int supportVertex(const ConvexHull& hull, const Vec3& direction);
// The same for the nearest vertex along `direction` (the farthest along
// −direction), starting from vertex `start`: the face queries' descent.
int lowestVertexFrom(const ConvexHull& hull, const Vec3& direction, int start);

// The convex hull of `points` (qhull). Rejects, with a message naming
// `sourceName`, fewer than 4 distinct points, and coplanar or collinear sets
// (zero volume).
Expected<ConvexHull> buildConvexHull(const std::vector<Vec3>& points, const std::string& sourceName);

}  // namespace rbsim
