// Mass properties of compound bodies: parts combined exactly (rotated
// tensors, parallel-axis shifts), checked against single solids that have
// the same shape and against a tensor worked out by hand.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "meshio/mesh_io.h"
#include "rbsim/physics/mass_properties.h"
#include "rbsim/physics/world.h"
#include "support/test_data_dir.h"

namespace rbsim {
namespace {

constexpr double kRelTol = 1e-12;
constexpr double kPi = std::numbers::pi;

const std::filesystem::path kLBlockMesh =
    (std::filesystem::path(rbsim::test_support::kTestDataDir) / ".." / ".." / "config" / "meshes" / "l_block.obj")
        .lexically_normal();

void expectRelNear(double actual, double expected, double relTol = kRelTol) {
  EXPECT_NEAR(actual, expected, relTol * std::abs(expected)) << "expected " << expected;
}

void expectVecNear(const Vec3& actual, const Vec3& expected, double absTol) {
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), absTol)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

void expectMatrixNear(const Mat3& actual, const Mat3& expected, double relTol = kRelTol) {
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), relTol * scale) << "actual\n"
                                                                       << actual << "\nexpected\n"
                                                                       << expected;
}

CompoundPart boxPart(const Vec3& halfExtents, const Vec3& position,
                     const Quaternion& orientation = Quaternion::identity()) {
  return CompoundPart{BoxShape{halfExtents}, position, orientation, std::nullopt};
}

BodyDef compoundBody(const std::string& name, std::vector<CompoundPart> parts, double density) {
  BodyDef def;
  def.name = name;
  def.shape = CompoundShape{std::move(parts)};
  def.density = density;
  return def;
}

TEST(CompoundMass, TwoBoxesSideBySideAreTheBoxTheyForm) {
  // Two 1 × 1 × 1 m cubes at x = ±0.5 m form the box [-1, 1] × [-0.5, 0.5]².
  const double density = 750.0;
  const MassProperties cube = boxMassProperties(Vec3::Constant(0.5), density);
  const std::vector<PlacedMassProperties> parts = {
      {cube, Transform{Mat3::Identity(), Vec3(-0.5, 0, 0)}},
      {cube, Transform{Mat3::Identity(), Vec3(0.5, 0, 0)}}};
  const MassProperties combined = combinedMassProperties(parts);
  const MassProperties whole = boxMassProperties(Vec3(1.0, 0.5, 0.5), density);
  expectRelNear(combined.mass, whole.mass);
  expectRelNear(combined.volume, whole.volume);
  expectVecNear(combined.centerOfMass, whole.centerOfMass, 1e-12);
  expectMatrixNear(combined.inertia, whole.inertia);

  // The same as a body: the same mass and principal moments, the same axes
  // (the tensor is diagonal), the centre of mass at the shape's origin.
  World world;
  BodyDef pair = compoundBody("pair",
                              {boxPart(Vec3::Constant(0.5), Vec3(-0.5, 0, 0)),
                               boxPart(Vec3::Constant(0.5), Vec3(0.5, 0, 0))},
                              density);
  pair.position = Vec3(1, 2, 3);
  BodyDef single;
  single.name = "single";
  single.shape = BoxShape{Vec3(1.0, 0.5, 0.5)};
  single.density = density;
  single.position = Vec3(1, 2, 3);
  const BodyView a = world.body(*world.createBody(pair));
  const BodyView b = world.body(*world.createBody(single));
  expectRelNear(a.mass(), b.mass());
  for (int k = 0; k < 3; ++k)
    expectRelNear(a.dynamics().inertiaBody[k], b.dynamics().inertiaBody[k]);
  expectVecNear(a.position(), b.position(), 1e-12);
  EXPECT_EQ(a.orientation().w, 1.0);
}

TEST(CompoundMass, LShapeOfTwoBoxesIsTheLBlockMesh) {
  // config/meshes/l_block.obj: [0, 0.4] × [0, 0.2] plus [0, 0.2] × [0.2, 0.4],
  // extruded over z in [0, 0.1].
  const Expected<TriangleMesh> mesh = loadMesh(kLBlockMesh.string());
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  const double density = 700.0;
  const MassProperties exact = polyhedronMassProperties(*mesh, density);
  const std::vector<PlacedMassProperties> parts = {
      {boxMassProperties(Vec3(0.2, 0.1, 0.05), density),
       Transform{Mat3::Identity(), Vec3(0.2, 0.1, 0.05)}},
      {boxMassProperties(Vec3(0.1, 0.1, 0.05), density),
       Transform{Mat3::Identity(), Vec3(0.1, 0.3, 0.05)}}};
  const MassProperties combined = combinedMassProperties(parts);
  expectRelNear(combined.mass, exact.mass);
  expectRelNear(combined.volume, exact.volume);
  expectVecNear(combined.centerOfMass, exact.centerOfMass, 1e-12);
  expectMatrixNear(combined.inertia, exact.inertia);
  // The closed form: the centre of mass of the L is (1/6, 1/6, 1/20) m.
  expectVecNear(combined.centerOfMass, Vec3(1.0 / 6.0, 1.0 / 6.0, 0.05), 1e-15);

  // As bodies: the same principal moments, and the same world centre of
  // mass when both shapes are put at the same pose.
  World world;
  BodyDef compound = compoundBody("l_compound",
                                  {boxPart(Vec3(0.2, 0.1, 0.05), Vec3(0.2, 0.1, 0.05)),
                                   boxPart(Vec3(0.1, 0.1, 0.05), Vec3(0.1, 0.3, 0.05))},
                                  density);
  BodyDef meshBody;
  meshBody.name = "l_mesh";
  meshBody.shape = MeshShape{kLBlockMesh.string(), std::make_shared<const TriangleMesh>(*mesh)};
  meshBody.density = density;
  for (BodyDef* def : {&compound, &meshBody}) {
    def->position = Vec3(-1.0, 0.5, 2.0);
    def->orientation = Quaternion::fromRollPitchYaw(0.3, -0.2, 1.1);
  }
  const BodyView a = world.body(*world.createBody(compound));
  const BodyView b = world.body(*world.createBody(meshBody));
  for (int k = 0; k < 3; ++k)
    expectRelNear(a.dynamics().inertiaBody[k], b.dynamics().inertiaBody[k], 1e-10);
  expectVecNear(a.position(), b.position(), 1e-12);
  expectMatrixNear(a.inertiaWorld(), b.inertiaWorld(), 1e-10);
}

TEST(CompoundMass, RotatedBoxOffCentreHasTheInertiaWorkedOutByHand) {
  // A box rotated by θ about z and moved to p, plus a sphere at the origin.
  const double density = 1000.0;
  const double a = 0.3, b = 0.1, c = 0.05;  // m, half extents
  const double theta = kPi / 6.0;
  const Vec3 p(0.4, 0.2, 0.1);
  const double radius = 0.1;

  const double boxMass = density * 8.0 * a * b * c;  // 12 kg
  // Box moments about its own axes: (m/3)(b² + c²) and cyclic, with half extents.
  const double ia = boxMass / 3.0 * (b * b + c * c);
  const double ib = boxMass / 3.0 * (a * a + c * c);
  const double ic = boxMass / 3.0 * (a * a + b * b);
  const double sphereMass = density * 4.0 / 3.0 * kPi * radius * radius * radius;
  const double is = 0.4 * sphereMass * radius * radius;

  // R I Rᵀ for a rotation by θ about z, element by element.
  const double cs = std::cos(theta), sn = std::sin(theta);
  const double rxx = cs * cs * ia + sn * sn * ib;
  const double ryy = sn * sn * ia + cs * cs * ib;
  const double rxy = cs * sn * (ia - ib);

  // Common centre of mass (the sphere sits at the origin).
  const double total = boxMass + sphereMass;
  const Vec3 com = boxMass / total * p;
  // Parallel-axis terms m (|d|² δij − di dj) for d = p − com (box) and d = −com (sphere).
  const Vec3 db = p - com, ds = -com;
  Mat3 expected;
  expected(0, 0) = rxx + boxMass * (db.y() * db.y() + db.z() * db.z()) + is +
                   sphereMass * (ds.y() * ds.y() + ds.z() * ds.z());
  expected(1, 1) = ryy + boxMass * (db.x() * db.x() + db.z() * db.z()) + is +
                   sphereMass * (ds.x() * ds.x() + ds.z() * ds.z());
  expected(2, 2) = ic + boxMass * (db.x() * db.x() + db.y() * db.y()) + is +
                   sphereMass * (ds.x() * ds.x() + ds.y() * ds.y());
  expected(0, 1) = expected(1, 0) = rxy - boxMass * db.x() * db.y() - sphereMass * ds.x() * ds.y();
  expected(0, 2) = expected(2, 0) = -boxMass * db.x() * db.z() - sphereMass * ds.x() * ds.z();
  expected(1, 2) = expected(2, 1) = -boxMass * db.y() * db.z() - sphereMass * ds.y() * ds.z();

  const Quaternion turn = Quaternion::fromAxisAngle(Vec3::UnitZ(), theta);
  const std::vector<PlacedMassProperties> parts = {
      {boxMassProperties(Vec3(a, b, c), density), Transform::fromPose(p, turn)},
      {sphereMassProperties(radius, density), Transform{}}};
  const MassProperties combined = combinedMassProperties(parts);
  expectRelNear(combined.mass, total);
  expectVecNear(combined.centerOfMass, com, 1e-15);
  expectMatrixNear(combined.inertia, expected);

  // As a body: principal moments are the eigenvalues of that tensor, the
  // centre of mass lands where the shape pose puts it, and the shape frame
  // sits in body space so that shape points map to the same world points.
  World world;
  BodyDef def = compoundBody(
      "lever",
      {boxPart(Vec3(a, b, c), p, turn),
       CompoundPart{SphereShape{radius}, Vec3::Zero(), Quaternion::identity(), std::nullopt}},
      density);
  def.position = Vec3(2.0, -1.0, 0.5);
  def.orientation = Quaternion::fromRollPitchYaw(0.4, 0.0, -0.7);
  const BodyView body = world.body(*world.createBody(def));
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(expected);
  for (int k = 0; k < 3; ++k)
    expectRelNear(body.dynamics().inertiaBody[k], eigen.eigenvalues()[k], 1e-11);
  expectVecNear(body.position(), def.position + def.orientation.rotate(com), 1e-12);
  const BodyDescription& d = body.description();
  for (const Vec3& shapePoint : {Vec3(0, 0, 0), p, Vec3(0.3, -0.4, 0.2)}) {
    const Vec3 viaBody = body.bodyToWorld(d.shapeRotation * shapePoint + d.shapeTranslation);
    expectVecNear(viaBody, def.position + def.orientation.rotate(shapePoint), 1e-12);
  }
}

TEST(CompoundMass, PartDensitiesWeighThePartsAndABodyMassScalesTheWhole) {
  // Two equal spheres, one three times as dense: the centre of mass sits
  // at 3/4 of the way to the dense one.
  const double radius = 0.1;
  const std::vector<CompoundPart> parts = {
      CompoundPart{SphereShape{radius}, Vec3(-1, 0, 0), Quaternion::identity(), std::nullopt},
      CompoundPart{SphereShape{radius}, Vec3(1, 0, 0), Quaternion::identity(), 3000.0}};
  const double volume = 4.0 / 3.0 * kPi * radius * radius * radius;

  World world;
  BodyDef byDensity = compoundBody("by_density", parts, 1000.0);
  byDensity.position = Vec3(0, 0, 0);
  const BodyView a = world.body(*world.createBody(byDensity));
  expectRelNear(a.mass(), 4000.0 * volume);
  expectVecNear(a.position(), Vec3(0.5, 0, 0), 1e-15);

  BodyDef byMass = compoundBody("by_mass", parts, 1000.0);
  byMass.density.reset();
  byMass.mass = 8.0;  // kg: 2 kg and 6 kg
  const BodyView b = world.body(*world.createBody(byMass));
  EXPECT_EQ(b.mass(), 8.0);
  expectVecNear(b.position(), Vec3(0.5, 0, 0), 1e-15);
  // About the y axis through the centre of mass: (2/5) m r² each plus
  // 2 kg at 1.5 m and 6 kg at 0.5 m.
  expectRelNear(b.dynamics().inertiaBody.y(),
                0.4 * 8.0 * radius * radius + 2.0 * 2.25 + 6.0 * 0.25);
}

TEST(CompoundMass, BadCompoundsAreRejectedByTheWorld) {
  World world;
  BodyDef empty = compoundBody("empty", {}, 1000.0);
  const auto none = world.createBody(empty);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().message, "body 'empty': a compound needs at least one part");

  BodyDef flat = compoundBody("flat", {boxPart(Vec3(1, 0, 1), Vec3::Zero())}, 1000.0);
  const auto zero = world.createBody(flat);
  ASSERT_FALSE(zero.ok());
  EXPECT_EQ(zero.error().message,
            "body 'flat': compound part 0: box half_extents must be positive");

  BodyDef turned = compoundBody(
      "turned", {boxPart(Vec3::Constant(1), Vec3::Zero(), Quaternion{0, 0, 0, 0})}, 1000.0);
  EXPECT_FALSE(world.createBody(turned).ok());
  EXPECT_EQ(world.bodyCount(), 0);
}

}  // namespace
}  // namespace rbsim
