// buildCollider for every shape (pieces and body-frame bounds against closed
// forms), meshes split into connected components, and the collider that
// World::createBody stores with each body.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geometry_test_helpers.h"
#include "physics/collision/collider.h"
#include "rbsim/physics/world.h"

namespace rbsim {
namespace {

// Box [center − h, center + h] as 8 vertices and 12 outward triangles,
// appended to `mesh`.
void appendBox(TriangleMesh& mesh, const Vec3& half, const Vec3& center) {
  const int base = static_cast<int>(mesh.vertices.size());
  for (const Vec3& c : testing::boxCorners(half)) mesh.vertices.push_back(center + c);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh.triangles.push_back({base + q[0], base + q[1], base + q[2]});
    mesh.triangles.push_back({base + q[0], base + q[2], base + q[3]});
  }
}

MeshShape meshShape(TriangleMesh mesh, const std::string& file = "two_boxes.obj") {
  return MeshShape{file, std::make_shared<const TriangleMesh>(std::move(mesh))};
}

void expectBounds(const Aabb& box, const Vec3& lo, const Vec3& hi, double tol = 1e-12) {
  EXPECT_LE((box.min - lo).cwiseAbs().maxCoeff(), tol)
      << box.min.transpose() << " vs " << lo.transpose();
  EXPECT_LE((box.max - hi).cwiseAbs().maxCoeff(), tol)
      << box.max.transpose() << " vs " << hi.transpose();
}

const Transform kShapeToBody{Quaternion::fromRollPitchYaw(0.2, -0.4, 0.9).toRotationMatrix(),
                             Vec3(0.1, -0.3, 0.2)};

TEST(Collider, PrimitivesAreOnePieceWithExactBodyBounds) {
  const Mat3& r = kShapeToBody.rotation;
  const Vec3& t = kShapeToBody.translation;
  const Vec3 axis = r.col(2);

  auto sphere = buildCollider(SphereShape{0.5}, kShapeToBody, "ball");
  ASSERT_TRUE(sphere.ok());
  ASSERT_EQ(sphere->pieces.size(), 1u);
  EXPECT_FALSE(sphere->plane.has_value());
  expectBounds(sphere->bounds, t - Vec3::Constant(0.5), t + Vec3::Constant(0.5));
  expectBounds(sphere->pieces[0].bounds, t - Vec3::Constant(0.5), t + Vec3::Constant(0.5));
  EXPECT_EQ(sphere->pieces[0].placement.translation, t);

  const Vec3 h(0.5, 0.25, 1.0);
  auto box = buildCollider(BoxShape{h}, kShapeToBody, "crate");
  ASSERT_TRUE(box.ok());
  const Vec3 boxHalf = r.cwiseAbs() * h;  // Arvo
  expectBounds(box->bounds, t - boxHalf, t + boxHalf);

  auto capsule = buildCollider(CapsuleShape{0.2, 0.6}, kShapeToBody, "pill");
  ASSERT_TRUE(capsule.ok());
  const Vec3 capsuleHalf = 0.6 * axis.cwiseAbs() + Vec3::Constant(0.2);
  expectBounds(capsule->bounds, t - capsuleHalf, t + capsuleHalf);

  auto cylinder = buildCollider(CylinderShape{0.3, 0.7}, kShapeToBody, "can");
  ASSERT_TRUE(cylinder.ok());
  Vec3 cylinderHalf;
  for (int i = 0; i < 3; ++i)
    cylinderHalf[i] = 0.7 * std::abs(axis[i]) + 0.3 * std::sqrt(1 - axis[i] * axis[i]);
  expectBounds(cylinder->bounds, t - cylinderHalf, t + cylinderHalf);
}

TEST(Collider, BadPrimitiveSizesAreErrorsNamingTheSource) {
  for (const Shape& shape :
       {Shape{SphereShape{0.0}}, Shape{BoxShape{Vec3(1, -1, 1)}}, Shape{CapsuleShape{0.0, 1.0}},
        Shape{CylinderShape{1.0, std::nan("")}}, Shape{PlaneShape{Vec3::Zero(), 0.0}}}) {
    const auto collider = buildCollider(shape, Transform{}, "body 'broken'");
    ASSERT_FALSE(collider.ok());
    EXPECT_NE(collider.error().message.find("body 'broken'"), std::string::npos)
        << collider.error().message;
  }
  // A capsule of zero cylindrical length is a sphere: allowed.
  EXPECT_TRUE(buildCollider(CapsuleShape{0.5, 0.0}, Transform{}, "ball").ok());
}

TEST(Collider, TwoComponentMeshGivesTwoHullPieces) {
  TriangleMesh mesh;
  appendBox(mesh, Vec3(0.5, 0.5, 0.5), Vec3(-2, 0, 0));
  appendBox(mesh, Vec3(0.25, 1.0, 0.5), Vec3(3, 1, 0));
  const auto collider = buildCollider(meshShape(mesh), Transform{}, "body 'dumbbell'");
  ASSERT_TRUE(collider.ok()) << collider.error().message;
  ASSERT_EQ(collider->pieces.size(), 2u);
  for (const auto& piece : collider->pieces) {
    const auto& hull = std::get<std::shared_ptr<const ConvexHull>>(piece.geometry);
    EXPECT_EQ(hull->vertices.size(), 8u);
    EXPECT_EQ(hull->faces.size(), 6u);
  }
  expectBounds(collider->pieces[0].bounds, Vec3(-2.5, -0.5, -0.5), Vec3(-1.5, 0.5, 0.5));
  expectBounds(collider->pieces[1].bounds, Vec3(2.75, 0.0, -0.5), Vec3(3.25, 2.0, 0.5));
  expectBounds(collider->bounds, Vec3(-2.5, -0.5, -0.5), Vec3(3.25, 2.0, 0.5));

  // Placed in the body frame: the pieces' bounds follow the transform.
  const auto moved = buildCollider(meshShape(mesh), kShapeToBody, "body 'dumbbell'");
  ASSERT_TRUE(moved.ok());
  for (int k = 0; k < 2; ++k) {
    const auto& hull = std::get<std::shared_ptr<const ConvexHull>>(
        moved->pieces[static_cast<std::size_t>(k)].geometry);
    Aabb expected;
    for (const Vec3& v : hull->vertices) expected.include(kShapeToBody.apply(v));
    expectBounds(moved->pieces[static_cast<std::size_t>(k)].bounds, expected.min, expected.max);
  }
}

TEST(Collider, UnweldedTrianglesStayOneComponent) {
  // A cube whose triangles each carry their own three vertex copies.
  TriangleMesh welded;
  appendBox(welded, Vec3::Constant(0.5), Vec3::Zero());
  TriangleMesh soup;
  for (const auto& tri : welded.triangles) {
    const int base = static_cast<int>(soup.vertices.size());
    for (int v : tri) soup.vertices.push_back(welded.vertices[static_cast<std::size_t>(v)]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  const auto collider = buildCollider(meshShape(soup, "soup.stl"), Transform{}, "body 'soup'");
  ASSERT_TRUE(collider.ok()) << collider.error().message;
  EXPECT_EQ(collider->pieces.size(), 1u);
}

TEST(Collider, DegenerateMeshComponentIsAnError) {
  TriangleMesh mesh;
  appendBox(mesh, Vec3::Constant(0.5), Vec3::Zero());
  // A second component that is flat: two triangles of a square.
  const int base = static_cast<int>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(),
                       {Vec3(3, 0, 0), Vec3(4, 0, 0), Vec3(4, 1, 0), Vec3(3, 1, 0)});
  mesh.triangles.push_back({base, base + 1, base + 2});
  mesh.triangles.push_back({base, base + 2, base + 3});
  const auto collider = buildCollider(meshShape(mesh, "flat.obj"), Transform{}, "body 'tile'");
  ASSERT_FALSE(collider.ok());
  const std::string& message = collider.error().message;
  EXPECT_NE(message.find("body 'tile'"), std::string::npos) << message;
  EXPECT_NE(message.find("flat.obj"), std::string::npos) << message;
  EXPECT_NE(message.find("component 1"), std::string::npos) << message;
  EXPECT_NE(message.find("coplanar"), std::string::npos) << message;

  EXPECT_FALSE(buildCollider(MeshShape{"missing.obj", nullptr}, Transform{}, "body 'ghost'").ok());
}

TEST(Collider, PlaneBecomesAHalfSpaceInTheBodyFrame) {
  // n · p <= d in the shape frame, with a non-unit normal.
  const PlaneShape plane{Vec3(0, 0, 2), 1.0};
  const auto collider = buildCollider(plane, kShapeToBody, "floor");
  ASSERT_TRUE(collider.ok());
  EXPECT_TRUE(collider->pieces.empty());
  ASSERT_TRUE(collider->plane.has_value());
  EXPECT_NEAR(collider->plane->normal.norm(), 1.0, 1e-15);
  // Points on the plane and inside it map to points on and inside the new one.
  scenes::SceneRandom random(4);
  for (int i = 0; i < 20; ++i) {
    const Vec3 p(random.uniform(-5, 5), random.uniform(-5, 5), random.uniform(-5, 5));
    const double shapeSide =
        plane.normal.dot(p) / 2.0 - plane.offset / 2.0;  // signed distance in the shape frame
    const Vec3 q = kShapeToBody.apply(p);
    EXPECT_NEAR(collider->plane->normal.dot(q) - collider->plane->offset, shapeSide, 1e-12);
  }
  EXPECT_EQ(collider->bounds.min, Aabb::everything().min);
  EXPECT_EQ(collider->bounds.max, Aabb::everything().max);
}

TEST(Collider, WorldStoresTheColliderOfEachBody) {
  World world;
  BodyDef ball;
  ball.name = "ball";
  ball.shape = SphereShape{0.3};
  const BodyId ballId = *world.createBody(ball);
  const auto& ballCollider = world.body(ballId).description().collider;
  ASSERT_NE(ballCollider, nullptr);
  ASSERT_EQ(ballCollider->pieces.size(), 1u);
  expectBounds(ballCollider->bounds, Vec3::Constant(-0.3), Vec3::Constant(0.3));

  // An off-centre mesh: the body frame sits at its centre of mass, so the
  // collider's bounds are centred on the origin of body space.
  TriangleMesh mesh;
  appendBox(mesh, Vec3(1.0, 0.5, 0.25), Vec3(5, 6, 7));
  BodyDef slab;
  slab.name = "slab";
  slab.shape = meshShape(mesh, "slab.obj");
  const BodyId slabId = *world.createBody(slab);
  const auto& slabCollider = world.body(slabId).description().collider;
  ASSERT_NE(slabCollider, nullptr);
  ASSERT_EQ(slabCollider->pieces.size(), 1u);
  EXPECT_LE(slabCollider->bounds.center().norm(), 1e-9);
  // Principal axes of a box are its own axes (in some order): the half
  // extents survive as a permutation.
  Vec3 half = slabCollider->bounds.halfExtents();
  std::sort(half.data(), half.data() + 3);
  EXPECT_LE((half - Vec3(0.25, 0.5, 1.0)).cwiseAbs().maxCoeff(), 1e-9);

  BodyDef floor;
  floor.name = "floor";
  floor.shape = PlaneShape{};
  floor.isStatic = true;
  const auto& floorCollider = world.body(*world.createBody(floor)).description().collider;
  ASSERT_NE(floorCollider, nullptr);
  EXPECT_TRUE(floorCollider->plane.has_value());
}

TEST(Collider, CompoundPartsArePiecesPlacedThroughTheirPoses) {
  // A box at the origin, a sphere at +x and a capsule turned along x at −x.
  const Quaternion alongX = Quaternion::fromAxisAngle(Vec3::UnitY(), 0.5 * std::numbers::pi);
  CompoundShape dumbbell;
  dumbbell.parts = {
      CompoundPart{BoxShape{Vec3(0.5, 0.05, 0.05)}, Vec3::Zero(), Quaternion::identity(), {}},
      CompoundPart{SphereShape{0.1}, Vec3(0.5, 0, 0), Quaternion::identity(), {}},
      CompoundPart{CapsuleShape{0.05, 0.2}, Vec3(-0.5, 0, 0), alongX, {}}};
  auto collider = buildCollider(dumbbell, kShapeToBody, "dumbbell");
  ASSERT_TRUE(collider.ok()) << collider.error().message;
  ASSERT_EQ(collider->pieces.size(), 3u);
  EXPECT_FALSE(collider->plane.has_value());
  EXPECT_TRUE(std::holds_alternative<BoxShape>(collider->pieces[0].geometry));
  EXPECT_TRUE(std::holds_alternative<SphereShape>(collider->pieces[1].geometry));
  EXPECT_TRUE(std::holds_alternative<CapsuleShape>(collider->pieces[2].geometry));

  // Each piece sits at shapeToBody ∘ partPose.
  const Mat3& r = kShapeToBody.rotation;
  const Vec3& t = kShapeToBody.translation;
  EXPECT_LE((collider->pieces[1].placement.translation - (r * Vec3(0.5, 0, 0) + t)).norm(), 1e-15);
  const Mat3 capsuleRotation = r * alongX.toRotationMatrix();
  EXPECT_LE((collider->pieces[2].placement.rotation - capsuleRotation).cwiseAbs().maxCoeff(),
            1e-15);
  // The capsule's axis (its z) now runs along the compound's x.
  EXPECT_LE((capsuleRotation.col(2) - r.col(0)).cwiseAbs().maxCoeff(), 1e-12);

  // The body's bounds are the union of the pieces' (each exact).
  const Vec3 sphereCenter = r * Vec3(0.5, 0, 0) + t;
  expectBounds(collider->pieces[1].bounds, sphereCenter - Vec3::Constant(0.1),
               sphereCenter + Vec3::Constant(0.1));
  Aabb united = Aabb::empty();
  for (const ConvexPiece& piece : collider->pieces) united = united.merged(piece.bounds);
  expectBounds(collider->bounds, united.min, united.max, 0.0);
  EXPECT_GT(collider->bounds.max.x() - collider->bounds.min.x(),
            collider->pieces[0].bounds.max.x() - collider->pieces[0].bounds.min.x());

  // A bad part names itself; an empty compound is refused.
  CompoundShape bad = dumbbell;
  bad.parts[1].shape = SphereShape{-1.0};
  auto refused = buildCollider(bad, Transform{}, "body 'dumbbell'");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message,
            "body 'dumbbell' compound part 1: sphere radius must be positive");
  EXPECT_FALSE(buildCollider(CompoundShape{}, Transform{}, "body 'none'").ok());
}

}  // namespace
}  // namespace rbsim
