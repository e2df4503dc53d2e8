// Every joint type writes exactly rowCount() errors and rows: the joint step
// packs the links' rows one after another into arrays sized by rowCount(),
// so a type writing more overruns its neighbour (a rope or a spring has no
// equality row at all; a fuzzed checkpoint found one writing past the end).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "physics/joint/joint_constraint.h"

namespace rbsim {
namespace {

struct Variant {
  const char* name;
  JointConstraint joint;
  int expectedRows;
};

std::vector<Variant> variants() {
  const auto of = [](JointType type) {
    JointConstraint joint;
    joint.def.type = type;
    joint.anchorA = Vec3(0.1, 0.0, 0.2);
    joint.anchorB = Vec3(-0.1, 0.05, 0.0);
    joint.length = 0.4;
    return joint;
  };
  JointConstraint rope = of(JointType::Distance);
  rope.def.limit.enabled = true;
  rope.def.limit.lower = 0.0;
  rope.def.limit.upper = 0.5;
  JointConstraint spring = of(JointType::Distance);
  spring.def.drive.enabled = true;
  spring.def.drive.target = 0.4;
  spring.def.drive.stiffness = 100.0;
  return {{"spherical", of(JointType::Spherical), 3}, {"revolute", of(JointType::Revolute), 5},
          {"prismatic", of(JointType::Prismatic), 5}, {"fixed", of(JointType::Fixed), 6},
          {"rod", of(JointType::Distance), 1},      {"rope", rope, 0},
          {"spring", spring, 0}};
}

TEST(JointRows, EveryTypeWritesExactlyItsRowCount) {
  const JointSidePose a{Vec3(0.0, 0.0, 1.0), Quaternion::identity(), Mat3::Identity()};
  const JointSidePose b{Vec3(0.3, 0.1, 0.9), Quaternion::identity(), Mat3::Identity()};
  const Vec3 sentinel(1234.5, -6.5, 7.25);
  for (const Variant& v : variants()) {
    SCOPED_TRACE(v.name);
    ASSERT_EQ(v.joint.rowCount(), v.expectedRows);
    const JointConstraint::Basis basis = v.joint.basisAt(a);

    std::array<double, kMaxJointRows + 1> errors;
    errors.fill(-99.0);
    v.joint.errors(a, b, basis, errors.data());
    for (int k = 0; k < v.expectedRows; ++k) EXPECT_NE(errors[k], -99.0) << "error " << k << " written";
    for (std::size_t k = static_cast<std::size_t>(v.expectedRows); k < errors.size(); ++k)
      EXPECT_EQ(errors[k], -99.0) << "error " << k << " is past rowCount()";

    std::array<JointRow, kMaxJointRows + 1> rows;
    rows.fill({sentinel, sentinel, sentinel, sentinel});
    v.joint.rows(a, b, basis, rows.data());
    for (std::size_t k = static_cast<std::size_t>(v.expectedRows); k < rows.size(); ++k)
      EXPECT_EQ(rows[k].linearA, sentinel) << "row " << k << " is past rowCount()";
  }
}

}  // namespace
}  // namespace rbsim
