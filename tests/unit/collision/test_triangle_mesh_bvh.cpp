// The trimesh BVH against brute force, and the active-edge classification.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "physics/collision/active_edges.h"
#include "physics/collision/triangle_mesh_bvh.h"
#include "physics/collision/triangle_mesh_collider.h"
#include "unit/collision/triangle_mesh_test_meshes.h"

namespace rbsim {
namespace {

Aabb triangleBox(const TriangleMesh& mesh, int t) {
  Aabb box = Aabb::empty();
  for (int v : mesh.triangles[static_cast<std::size_t>(t)])
    box.include(mesh.vertices[static_cast<std::size_t>(v)]);
  return box;
}

TEST(TriangleMeshBvh, ReportsExactlyTheTrianglesWhoseBoxesOverlapTheQuery) {
  std::mt19937 random(40);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  std::uniform_real_distribution<double> size(0.01, 2.0);
  for (int trial = 0; trial < 20; ++trial) {
    // Random triangles of random sizes, scattered.
    TriangleMesh mesh;
    const int count = 1 + trial * 37;
    for (int t = 0; t < count; ++t) {
      const Vec3 corner(coordinate(random), coordinate(random), coordinate(random));
      const int first = static_cast<int>(mesh.vertices.size());
      mesh.vertices.push_back(corner);
      mesh.vertices.push_back(corner + Vec3(size(random), 0.1 * size(random), 0.0));
      mesh.vertices.push_back(corner + Vec3(0.0, size(random), size(random)));
      mesh.triangles.push_back({first, first + 1, first + 2});
    }
    std::vector<Aabb> boxes;
    for (int t = 0; t < count; ++t) boxes.push_back(triangleBox(mesh, t));
    const TriangleMeshBvh bvh(boxes);
    // Every triangle sits in exactly one leaf.
    std::vector<int> order = bvh.triangleOrder();
    std::sort(order.begin(), order.end());
    for (int t = 0; t < count; ++t) ASSERT_EQ(order[static_cast<std::size_t>(t)], t);
    for (int q = 0; q < 50; ++q) {
      const Vec3 centre(coordinate(random), coordinate(random), coordinate(random));
      const Vec3 half(size(random), size(random), size(random));
      const Aabb query{centre - half, centre + half};
      std::vector<int> found;
      bvh.forEachOverlap(query, [&found](int t) { found.push_back(t); });
      std::sort(found.begin(), found.end());
      std::vector<int> expected;
      for (int t = 0; t < count; ++t)
        if (boxes[static_cast<std::size_t>(t)].overlaps(query)) expected.push_back(t);
      ASSERT_EQ(found, expected) << "trial " << trial << ", query " << q;
    }
  }
}

TEST(TriangleMeshBvh, AnEmptyTreeReportsNothing) {
  const TriangleMeshBvh bvh(std::vector<Aabb>{});
  int visits = 0;
  bvh.forEachOverlap(Aabb::everything(), [&visits](int) { ++visits; });
  EXPECT_EQ(visits, 0);
  EXPECT_TRUE(bvh.bounds().isEmpty());
}

int activeEdgeCount(const std::vector<uint8_t>& flags) {
  int count = 0;
  for (uint8_t f : flags) count += (f & 1) + ((f >> 1) & 1) + ((f >> 2) & 1);
  return count;
}

TEST(ActiveEdges, AFlatGridHasOnlyItsBorderActive) {
  const TriangleMesh grid = testing::flatGrid(10, 5.0);
  const std::vector<uint8_t> flags = findActiveEdges(grid.vertices, grid.triangles);
  // The border: 4 sides of 10 cells; every interior and diagonal edge is flat.
  EXPECT_EQ(activeEdgeCount(flags), 40);
  for (std::size_t t = 0; t < grid.triangles.size(); ++t) {
    for (int e = 0; e < 3; ++e) {
      const Vec3& a = grid.vertices[static_cast<std::size_t>(grid.triangles[t][static_cast<std::size_t>(e)])];
      const Vec3& b = grid.vertices[static_cast<std::size_t>(grid.triangles[t][static_cast<std::size_t>((e + 1) % 3)])];
      const bool onBorder = (std::abs(a.x()) == 5.0 && a.x() == b.x()) ||
                            (std::abs(a.y()) == 5.0 && a.y() == b.y());
      EXPECT_EQ((flags[t] >> e) & 1, onBorder ? 1 : 0) << "triangle " << t << " edge " << e;
    }
  }
}

TEST(ActiveEdges, AnUnweldedGridFindsItsNeighboursByPosition) {
  // Every triangle with vertices of its own, as STL files come.
  const TriangleMesh welded = testing::flatGrid(4, 1.0);
  TriangleMesh loose;
  for (const auto& t : welded.triangles) {
    const int first = static_cast<int>(loose.vertices.size());
    for (int v : t) loose.vertices.push_back(welded.vertices[static_cast<std::size_t>(v)]);
    loose.triangles.push_back({first, first + 1, first + 2});
  }
  EXPECT_EQ(activeEdgeCount(findActiveEdges(loose.vertices, loose.triangles)), 16);
}

TEST(ActiveEdges, AConvexRidgeIsActiveAndAConcaveValleyIsNot) {
  const TriangleMesh step = testing::stepMesh(0.5);
  const std::vector<uint8_t> flags = findActiveEdges(step.vertices, step.triangles);
  // Edge e of a triangle runs from its vertex e to vertex e + 1. The
  // concave floor–wall edge (1, 2) is triangle 0's edge 1 and triangle 3's
  // edge 2.
  EXPECT_EQ((flags[0] >> 1) & 1, 0) << "floor side of the concave edge";
  EXPECT_EQ((flags[3] >> 2) & 1, 0) << "wall side of the concave edge";
  // The convex wall–top edge (4, 5) is triangle 2's edge 1 and triangle 5's edge 2.
  EXPECT_EQ((flags[2] >> 1) & 1, 1) << "wall side of the convex ridge";
  EXPECT_EQ((flags[5] >> 2) & 1, 1) << "top side of the convex ridge";
  // The floor's diagonal is flat: inactive on both sides.
  EXPECT_EQ((flags[0] >> 2) & 1, 0);
  EXPECT_EQ((flags[1] >> 0) & 1, 0);
  // The floor's far border x = −2 is a boundary: active.
  EXPECT_EQ((flags[1] >> 2) & 1, 1);
}

TEST(ActiveEdges, AGentleRidgeBelowTheThresholdIsInactive) {
  // Two triangles each tilted down by 2° from their shared edge (a convex
  // fold whose normals differ by 4°, under the 5° threshold), then by 4° (8°).
  for (const double degrees : {2.0, 4.0}) {
    const double angle = degrees * M_PI / 180.0;
    TriangleMesh roof;
    roof.vertices = {{0, -1, 0}, {0, 1, 0}, {-1, 0, -std::tan(angle)}, {1, 0, -std::tan(angle)}};
    roof.triangles = {{0, 1, 2}, {1, 0, 3}};
    const std::vector<uint8_t> flags = findActiveEdges(roof.vertices, roof.triangles);
    const int shared = flags[0] & 1;
    EXPECT_EQ(shared, 2.0 * degrees > 5.0 ? 1 : 0) << degrees << "°";
    EXPECT_EQ(flags[1] & 1, shared) << "both sides agree";
  }
}

TEST(TriangleMeshCollider, RejectsDegenerateTrianglesAndBadIndicesNamingThem) {
  TriangleMesh mesh = testing::flatGrid(1, 1.0);
  mesh.vertices.push_back({0.0, 0.0, 0.0});
  mesh.triangles.push_back({0, 3, 4});  // 4 lies on the diagonal from 0 to 3: zero area
  const auto degenerate = buildTriangleMeshCollider(mesh, Transform::identity(), "floor.obj");
  ASSERT_FALSE(degenerate);
  EXPECT_NE(degenerate.error().message.find("floor.obj"), std::string::npos);
  EXPECT_NE(degenerate.error().message.find("triangle 2"), std::string::npos);
  EXPECT_NE(degenerate.error().message.find("zero area"), std::string::npos);

  mesh.triangles.back() = {0, 1, 9};
  const auto outOfRange = buildTriangleMeshCollider(mesh, Transform::identity(), "floor.obj");
  ASSERT_FALSE(outOfRange);
  EXPECT_NE(outOfRange.error().message.find("triangle 2 has vertex index 9"), std::string::npos);
}

}  // namespace
}  // namespace rbsim
