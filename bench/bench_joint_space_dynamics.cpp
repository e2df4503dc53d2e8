// The joint-space dynamics of the seven-joint example arm
// (config/robots/arm7.urdf, fixed base, bent, moving): the model read from
// the world, then M(q), h(q, q̇) and one link point's Jacobian, as a
// model-based controller asks for them each cycle. The target:
// all of it within 20 µs.
//
// When orocos KDL is installed (Debian: apt-get install -y
// liborocos-kdl-dev; bench/CMakeLists.txt builds the KDL part only then),
// the same quantities from KDL on the same model, side by side (issue 37:
// rbsim's own recursive algorithms must be shown faster than a well-kept
// library's to be kept), and the run first checks that both describe the
// same model: M, g, C(q, q̇)q̇ + g against rbsim's h, C(q, q̇)q̇ against
// h − g, and the Jacobian, each to 1e-9 relative (the largest difference
// over the largest entry); it prints them and fails when they disagree.
//
// KDL's model is built from the world as rbsim simulates it, not from the
// URDF (kdlArmOfWorld below): one KDL::Segment per joint of the robot,
// base to tip, from the joints' states (the world's anchor on the parent
// body, the world's axis, the joint's coordinate) and the bodies (mass,
// centre of mass, inertia about it, world frame), at the world's current
// state. Every segment's frames are world-aligned at the current joint
// positions: a segment's joint is KDL::Joint(anchor, axis, RotAxis) in
// world coordinates, its tip frame the inverse of that joint's pose at the
// joint's current position q_i, so that at q (rbsim's JointState
// positions, which KDL is fed) every segment's tip frame is the world
// frame (the last segment's moved to link7's centre of mass, the point
// whose Jacobian is asked for), and its KDL::RigidBodyInertia is the
// body's, world frame. KDL then turns each body rigidly about the same
// axis through the same anchor as rbsim's model does, and is fed rbsim's
// q and q̇: the same model, at q and, the bodies being rigid, about it
// (rbsim's model is a snapshot at q: it is read from the world each time).
//
// Benchmarks (µs per controller cycle):
//   rbsim/model_from_world+M+h+J  JointSpaceDynamics::ofRobot, massMatrix, biasForces, jacobian
//   kdl/model_from_world+M+h+J    kdlArmOfWorld, ChainDynParam and ChainJntToJacSolver made,
//                                 JntToMass, JntToCoriolis + JntToGravity, JntToJac
//   rbsim/M+h+J                   the three on a model already read
//   kdl/M+h+J                     the same KDL calls on a chain and solvers already made
//   kdl/M+h(one_RNE)+J            KDL's quicker h: ChainIdSolver_RNE with q̈ = 0 (one pass, not two)
//   kdl/q_qd_from_world+…         the chain made once, each cycle the joints' q and q̇ read
//                                 from the world, then M+h+J or M+h(one_RNE)+J
//
//   taskset -c 1 build/bench/bench_joint_space_dynamics --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Figures (bench/README.md, "Joint-space dynamics").
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "rbsim/physics/body_view.h"
#include "rbsim/physics/joint_definition.h"
#include "rbsim/physics/joint_space_dynamics.h"
#include "rbsim/physics/world.h"
#include "robot/urdf_robot.h"

#if RBSIM_BENCH_KDL
#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl/jacobian.hpp>
#include <kdl/jntarray.hpp>
#include <kdl/jntspaceinertiamatrix.hpp>
#endif

namespace {

constexpr const char* kJoints[] = {"arm/joint1", "arm/joint2", "arm/joint3", "arm/joint4",
                                   "arm/joint5", "arm/joint6", "arm/joint7"};

// Every joint of the arm set moving: efforts on each for 0.1 s (as
// tests/unit/joint/test_joint_space_dynamics.cpp's setMoving), then none
// (gravity alone) for 0.02 s.
void setMoving(rbsim::World& world) {
  const double efforts[] = {6.0, -12.0, 3.0, 6.0, 1.0, -1.5, 0.5};  // N·m
  for (int k = 0; k < 7; ++k)
    if (!world.setJointEffort(world.findJoint(kJoints[k]), efforts[k]).ok()) std::exit(1);
  for (int k = 0; k < 100; ++k) world.step();
  for (int k = 0; k < 7; ++k)
    if (!world.setJointEffort(world.findJoint(kJoints[k]), 0.0).ok()) std::exit(1);
  for (int k = 0; k < 20; ++k) world.step();
}

// The arm bent, at rest as loaded or (`moving`) set moving.
rbsim::World bentArm(bool moving = true) {
  using namespace rbsim;
  RobotPlacement placement;
  placement.name = "arm";
  placement.fixedBase = true;
  placement.jointPositions = {{"joint2", 0.6}, {"joint3", 0.4}, {"joint4", -1.2}, {"joint6", 0.8}};
  RobotFiles files;
  files.sourceName = "arm7.urdf";
  Expected<RobotModel> robot = loadRobot(std::string(RBSIM_SOURCE_DIR) + "/config/robots/arm7.urdf", placement, files);
  if (!robot) {
    std::fprintf(stderr, "%s\n", robot.error().message.c_str());
    std::exit(1);
  }
  WorldDef def;
  def.settings.gravity = Vec3(0, 0, -9.81);
  def.bodies = robot->bodies;
  def.joints = robot->joints;
  Expected<World> world = World::fromDef(def);
  if (!world) {
    std::fprintf(stderr, "%s\n", world.error().message.c_str());
    std::exit(1);
  }
  if (moving) setMoving(*world);
  return std::move(*world);
}

rbsim::Vec3 toolPoint(const rbsim::World& world) { return world.body(world.findBody("arm/link7")).position(); }

void RbsimModelFromWorld(benchmark::State& state) {
  const rbsim::World world = bentArm();
  const rbsim::Vec3 tool = toolPoint(world);
  for (auto _ : state) {
    const auto dynamics = rbsim::JointSpaceDynamics::ofRobot(world, "arm/");
    benchmark::DoNotOptimize(dynamics->massMatrix());
    benchmark::DoNotOptimize(dynamics->biasForces());
    benchmark::DoNotOptimize(dynamics->jacobian("arm/link7", tool));
  }
}
BENCHMARK(RbsimModelFromWorld)->Name("rbsim/model_from_world+M+h+J")->Unit(benchmark::kMicrosecond);

// The three alone, on a model already read.
void RbsimOnModel(benchmark::State& state) {
  const rbsim::World world = bentArm();
  const rbsim::Vec3 tool = toolPoint(world);
  const auto dynamics = rbsim::JointSpaceDynamics::ofRobot(world, "arm/");
  for (auto _ : state) {
    benchmark::DoNotOptimize(dynamics->massMatrix());
    benchmark::DoNotOptimize(dynamics->biasForces());
    benchmark::DoNotOptimize(dynamics->jacobian("arm/link7", tool));
  }
}
BENCHMARK(RbsimOnModel)->Name("rbsim/M+h+J")->Unit(benchmark::kMicrosecond);

#if RBSIM_BENCH_KDL

KDL::Vector kdl(const rbsim::Vec3& v) { return KDL::Vector(v.x(), v.y(), v.z()); }

// A robot of the world as a KDL chain (see the top of the file): its
// segments base to tip, one per joint whose name starts with `prefix`, and
// its coordinates' positions and rates as the world's joint states report
// them. A serial robot with a fixed base only (the world or a static body):
// KDL's ChainDynParam is for chains.
struct KdlArm {
  KDL::Chain chain;
  KDL::JntArray q, qd;
  std::vector<int> coordinateJoints;  // the world's dense joint index of each coordinate
  KDL::Vector gravity;
};

// A chain made once, fed the world's current joint positions and rates.
void readJointStates(const rbsim::World& world, KdlArm& arm) {
  for (std::size_t k = 0; k < arm.coordinateJoints.size(); ++k) {
    const rbsim::JointState state = world.jointStateAt(arm.coordinateJoints[k]);
    arm.q(static_cast<unsigned>(k)) = state.position;
    arm.qd(static_cast<unsigned>(k)) = state.rate;
  }
}

bool kdlArmOfWorld(const rbsim::World& world, std::string_view prefix, KdlArm& out, std::string* error = nullptr) {
  using namespace rbsim;
  const auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  struct Joint {
    int index;
    BodyId parent, child;
  };
  std::vector<Joint> joints;
  for (int j = 0; j < world.jointCount(); ++j) {
    const JointDef& def = world.jointDefinitionAt(j);
    if (def.name.compare(0, prefix.size(), prefix) != 0) continue;
    if (def.type != JointType::Revolute && def.type != JointType::Prismatic && def.type != JointType::Fixed)
      return fail("joint '" + def.name + "' is neither revolute, prismatic nor fixed");
    joints.push_back({j, def.bodyA, def.bodyB});
  }
  // The base: the parent that no joint of the robot carries.
  const auto carried = [&](BodyId body) {
    return std::any_of(joints.begin(), joints.end(), [&](const Joint& joint) { return joint.child == body; });
  };
  BodyId at{};
  bool found = false;
  for (const Joint& joint : joints)
    if (!carried(joint.parent)) {
      if (found && !(joint.parent == at)) return fail("two bases");
      at = joint.parent;
      found = true;
    }
  if (!found) return fail("no base");
  if (!at.isNull() && !world.body(at).isStatic()) return fail("a floating base: not a KDL chain");
  out.chain = KDL::Chain();
  out.coordinateJoints.clear();
  std::vector<double> q, qd;
  for (std::size_t placed = 0; placed < joints.size(); ++placed) {
    const Joint* next = nullptr;
    for (const Joint& joint : joints)
      if (joint.parent == at) {
        if (next) return fail("a branch: not a chain");
        next = &joint;
      }
    if (!next) return fail("a body the chain does not reach");
    const JointState state = world.jointStateAt(next->index);
    const BodyView body = world.body(next->child);
    // The tip frame: the world frame translated to `origin`, the world's
    // origin but for the chain's last body, whose centre of mass it is
    // (the point whose Jacobian the benchmark asks for).
    const bool last = std::none_of(joints.begin(), joints.end(), [&](const Joint& joint) { return joint.parent == next->child; });
    const KDL::Frame tip(last ? kdl(body.position()) : KDL::Vector::Zero());
    const Mat3 inertia = body.inertiaWorld();  // about the centre of mass, world
    const KDL::RigidBodyInertia rigid(
        body.mass(), kdl(body.position()) - tip.p,
        KDL::RotationalInertia(inertia(0, 0), inertia(1, 1), inertia(2, 2), inertia(0, 1), inertia(0, 2), inertia(1, 2)));
    if (state.type == JointType::Fixed) {
      out.chain.addSegment(KDL::Segment(KDL::Joint(KDL::Joint::Fixed), tip, rigid));
    } else {
      const KDL::Joint joint(kdl(state.anchorA), kdl(state.axis),
                             state.type == JointType::Revolute ? KDL::Joint::RotAxis : KDL::Joint::TransAxis);
      // That tip frame when the joint is at its position. KDL::Segment
      // takes the tip frame as it is at q = 0 (it keeps joint.pose(0)⁻¹ f_tip
      // and its pose(q) is joint.pose(q) times that).
      out.chain.addSegment(KDL::Segment(joint, joint.pose(0.0) * joint.pose(state.position).Inverse() * tip, rigid));
      q.push_back(state.position);
      qd.push_back(state.rate);
      out.coordinateJoints.push_back(next->index);
    }
    at = next->child;
  }
  out.q.resize(static_cast<unsigned>(q.size()));
  out.qd.resize(static_cast<unsigned>(qd.size()));
  for (std::size_t k = 0; k < q.size(); ++k) {
    out.q(static_cast<unsigned>(k)) = q[k];
    out.qd(static_cast<unsigned>(k)) = qd[k];
  }
  out.gravity = kdl(world.settings().gravity);
  return true;
}

// M, h = C(q, q̇)q̇ + g and the Jacobian of the chain's tip (the last
// body's centre of mass), the way a KDL user gets them from ChainDynParam
// and ChainJntToJacSolver.
struct KdlOutputs {
  KDL::JntSpaceInertiaMatrix mass;
  KDL::JntArray coriolis, gravity, bias;
  KDL::Jacobian jacobian;
  explicit KdlOutputs(unsigned n) : mass(n), coriolis(n), gravity(n), bias(n), jacobian(n) {}
};

void kdlMassBiasJacobian(const KdlArm& arm, KDL::ChainDynParam& dynamics, KDL::ChainJntToJacSolver& jacobians,
                         KdlOutputs& out) {
  dynamics.JntToMass(arm.q, out.mass);
  dynamics.JntToCoriolis(arm.q, arm.qd, out.coriolis);
  dynamics.JntToGravity(arm.q, out.gravity);
  KDL::Add(out.coriolis, out.gravity, out.bias);
  jacobians.JntToJac(arm.q, out.jacobian);
}

KdlArm kdlArmOrExit(const rbsim::World& world) {
  KdlArm arm;
  std::string error;
  if (!kdlArmOfWorld(world, "arm/", arm, &error)) {
    std::fprintf(stderr, "KDL model: %s\n", error.c_str());
    std::exit(1);
  }
  return arm;
}

void KdlModelFromWorld(benchmark::State& state) {
  const rbsim::World world = bentArm();
  KdlOutputs out(7);
  for (auto _ : state) {
    KdlArm arm;
    if (!kdlArmOfWorld(world, "arm/", arm)) state.SkipWithError("KDL model");
    KDL::ChainDynParam dynamics(arm.chain, arm.gravity);
    KDL::ChainJntToJacSolver jacobians(arm.chain);
    kdlMassBiasJacobian(arm, dynamics, jacobians, out);
    benchmark::DoNotOptimize(out.mass.data.data());
    benchmark::DoNotOptimize(out.bias.data.data());
    benchmark::DoNotOptimize(out.jacobian.data.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(KdlModelFromWorld)->Name("kdl/model_from_world+M+h+J")->Unit(benchmark::kMicrosecond);

void KdlOnModel(benchmark::State& state) {
  const rbsim::World world = bentArm();
  const KdlArm arm = kdlArmOrExit(world);
  KDL::ChainDynParam dynamics(arm.chain, arm.gravity);
  KDL::ChainJntToJacSolver jacobians(arm.chain);
  KdlOutputs out(arm.chain.getNrOfJoints());
  for (auto _ : state) {
    kdlMassBiasJacobian(arm, dynamics, jacobians, out);
    benchmark::DoNotOptimize(out.mass.data.data());
    benchmark::DoNotOptimize(out.bias.data.data());
    benchmark::DoNotOptimize(out.jacobian.data.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(KdlOnModel)->Name("kdl/M+h+J")->Unit(benchmark::kMicrosecond);

// KDL as a controller would keep it: the chain and solvers made once (its
// model holds for any q: the bodies turn rigidly about the joints' axes),
// each cycle only the joints' positions and rates read from the world.
// Not quite rbsim's model at a later state: the world's joints hold their
// bodies to within the position solver's error, which moves the anchors
// and axes by that much (the start-up check prints by how much).
void KdlReadStatesOnModel(benchmark::State& state) {
  const rbsim::World world = bentArm();
  KdlArm arm = kdlArmOrExit(world);
  KDL::ChainDynParam dynamics(arm.chain, arm.gravity);
  KDL::ChainJntToJacSolver jacobians(arm.chain);
  KdlOutputs out(arm.chain.getNrOfJoints());
  for (auto _ : state) {
    readJointStates(world, arm);
    kdlMassBiasJacobian(arm, dynamics, jacobians, out);
    benchmark::DoNotOptimize(out.mass.data.data());
    benchmark::DoNotOptimize(out.bias.data.data());
    benchmark::DoNotOptimize(out.jacobian.data.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(KdlReadStatesOnModel)->Name("kdl/q_qd_from_world+M+h+J")->Unit(benchmark::kMicrosecond);

// KDL's quickest route to h: one Newton–Euler pass with q̈ = 0 (what
// rbsim's biasForces does), rather than ChainDynParam's Coriolis and
// gravity passes.
void KdlOnModelOneRne(benchmark::State& state) {
  const rbsim::World world = bentArm();
  const KdlArm arm = kdlArmOrExit(world);
  const unsigned n = arm.chain.getNrOfJoints();
  KDL::ChainDynParam dynamics(arm.chain, arm.gravity);
  KDL::ChainIdSolver_RNE newtonEuler(arm.chain, arm.gravity);
  KDL::ChainJntToJacSolver jacobians(arm.chain);
  const KDL::JntArray zero(n);
  const KDL::Wrenches noWrenches(arm.chain.getNrOfSegments(), KDL::Wrench::Zero());
  KdlOutputs out(n);
  for (auto _ : state) {
    dynamics.JntToMass(arm.q, out.mass);
    newtonEuler.CartToJnt(arm.q, arm.qd, zero, noWrenches, out.bias);
    jacobians.JntToJac(arm.q, out.jacobian);
    benchmark::DoNotOptimize(out.mass.data.data());
    benchmark::DoNotOptimize(out.bias.data.data());
    benchmark::DoNotOptimize(out.jacobian.data.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(KdlOnModelOneRne)->Name("kdl/M+h(one_RNE)+J")->Unit(benchmark::kMicrosecond);

// Both: KDL's quickest controller cycle.
void KdlReadStatesOnModelOneRne(benchmark::State& state) {
  const rbsim::World world = bentArm();
  KdlArm arm = kdlArmOrExit(world);
  const unsigned n = arm.chain.getNrOfJoints();
  KDL::ChainDynParam dynamics(arm.chain, arm.gravity);
  KDL::ChainIdSolver_RNE newtonEuler(arm.chain, arm.gravity);
  KDL::ChainJntToJacSolver jacobians(arm.chain);
  const KDL::JntArray zero(n);
  const KDL::Wrenches noWrenches(arm.chain.getNrOfSegments(), KDL::Wrench::Zero());
  KdlOutputs out(n);
  for (auto _ : state) {
    readJointStates(world, arm);
    dynamics.JntToMass(arm.q, out.mass);
    newtonEuler.CartToJnt(arm.q, arm.qd, zero, noWrenches, out.bias);
    jacobians.JntToJac(arm.q, out.jacobian);
    benchmark::DoNotOptimize(out.mass.data.data());
    benchmark::DoNotOptimize(out.bias.data.data());
    benchmark::DoNotOptimize(out.jacobian.data.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(KdlReadStatesOnModelOneRne)->Name("kdl/q_qd_from_world+M+h(one_RNE)+J")->Unit(benchmark::kMicrosecond);

// The largest difference over the largest entry of rbsim's.
double relative(const Eigen::MatrixXd& kdlValue, const Eigen::MatrixXd& rbsimValue) {
  return (kdlValue - rbsimValue).cwiseAbs().maxCoeff() / rbsimValue.cwiseAbs().maxCoeff();
}

// Both libraries on the moving arm: the same model, or the run fails.
bool kdlAgreesWithRbsim() {
  const rbsim::World world = bentArm();
  const rbsim::Vec3 tool = toolPoint(world);
  const auto dynamics = rbsim::JointSpaceDynamics::ofRobot(world, "arm/");
  if (!dynamics) {
    std::fprintf(stderr, "rbsim: %s\n", dynamics.error().message.c_str());
    return false;
  }
  const KdlArm arm = kdlArmOrExit(world);
  const unsigned n = arm.chain.getNrOfJoints();
  if (static_cast<int>(n) != dynamics->dofCount()) {
    std::fprintf(stderr, "KDL has %u coordinates, rbsim %d\n", n, dynamics->dofCount());
    return false;
  }
  KDL::ChainDynParam kdlDynamics(arm.chain, arm.gravity);
  KDL::ChainJntToJacSolver kdlJacobians(arm.chain);
  KdlOutputs out(n);
  kdlMassBiasJacobian(arm, kdlDynamics, kdlJacobians, out);

  const Eigen::VectorXd rates = dynamics->velocities();
  std::printf("KDL against rbsim on the moving arm, qd (rad/s) =");
  for (Eigen::Index k = 0; k < rates.size(); ++k) std::printf(" %.3f", rates[k]);
  std::printf("\n");
  bool ok = rates.cwiseAbs().minCoeff() > 0.05;
  if (!ok) std::printf("  a joint is not moving: the check needs every rate\n");
  const Eigen::VectorXd bias = dynamics->biasForces(), gravity = dynamics->gravityTorques();
  const struct {
    const char* what;
    double value;
  } rows[] = {
      {"M (JntToMass vs massMatrix)", relative(out.mass.data, dynamics->massMatrix())},
      {"g (JntToGravity vs gravityTorques)", relative(out.gravity.data, gravity)},
      {"C qd + g (JntToCoriolis + JntToGravity vs biasForces)", relative(out.bias.data, bias)},
      {"C qd (JntToCoriolis vs biasForces - gravityTorques)", relative(out.coriolis.data, bias - gravity)},
      {"J of link7's centre of mass (JntToJac vs jacobian)", relative(out.jacobian.data, *dynamics->jacobian("arm/link7", tool))},
  };
  for (const auto& row : rows) {
    const bool agrees = row.value <= 1e-9;  // NaN fails
    std::printf("  %-58s relative difference %.2e %s\n", row.what, row.value, agrees ? "ok" : "> 1e-9: DISAGREE");
    ok = ok && agrees;
  }
  // Not checked, for the record: a chain made from the arm at rest (bent,
  // as loaded) and fed the moving arm's q and q̇, against rbsim's model of
  // the moving arm: the drift of the world's joints (maximal coordinates)
  // between the two states.
  {
    rbsim::World atRest = bentArm(false);
    KdlArm early = kdlArmOrExit(atRest);
    setMoving(atRest);
    readJointStates(atRest, early);
    const auto later = rbsim::JointSpaceDynamics::ofRobot(atRest, "arm/");
    KDL::ChainDynParam earlyDynamics(early.chain, early.gravity);
    KDL::ChainJntToJacSolver earlyJacobians(early.chain);
    KdlOutputs earlyOut(n);
    const rbsim::Vec3 laterTool = toolPoint(atRest);
    kdlMassBiasJacobian(early, earlyDynamics, earlyJacobians, earlyOut);
    std::printf("  (not checked) a chain made at rest, fed the moving state: M %.1e, h %.1e, J %.1e relative\n",
                relative(earlyOut.mass.data, later->massMatrix()), relative(earlyOut.bias.data, later->biasForces()),
                relative(earlyOut.jacobian.data, *later->jacobian("arm/link7", laterTool)));
  }
  std::fflush(stdout);
  return ok;
}

#endif  // RBSIM_BENCH_KDL

}  // namespace

int main(int argc, char** argv) {
#if RBSIM_BENCH_KDL
  if (!kdlAgreesWithRbsim()) {
    std::fprintf(stderr, "KDL and rbsim do not describe the same model: no benchmark run\n");
    return 1;
  }
#endif
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
