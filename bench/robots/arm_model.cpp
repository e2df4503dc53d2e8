#include "arm_model.h"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <utility>
#include <vector>

#include "inverse_diagonal.h"
#include "bench_paths.h"
#include "rbsim/physics/world.h"
#include "robot/urdf_robot.h"

namespace rbsim::bench::robots {

namespace {

// The start pose: config/worlds/robot_arm.yaml's.
const std::map<std::string, double, std::less<>> kStartPose = {
    {"joint2", 0.6}, {"joint4", 1.2}, {"joint6", 0.8}};

Vec3 plain(const rbsim::Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

Pose poseOf(const BodyView& body) {
  const Quaternion& q = body.orientation();
  return {plain(body.position()), {q.w, q.x, q.y, q.z}};
}

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "arm model: %s\n", message.c_str());
  std::exit(1);
}

// The diagonal of M⁻¹, M the joint-space mass matrix of the scene's start
// pose: M = Σ over links of m Jvᵀ Jv + Jwᵀ I Jw, where a joint k above the
// link moves its centre of mass c by a_k × (c − anchor_k) and turns it
// about a_k per unit rate.
std::vector<double> inverseMassDiagonal(const ArmScene& s, const std::vector<int>& parentOf) {
  const size_t n = s.joints.size();
  std::vector<double> m(n * n, 0.0);
  for (size_t i = 0; i < s.links.size(); ++i) {
    const LinkSpec& link = s.links[i];
    std::vector<size_t> above;  // the joints that move this link: joint k moves link k
    for (int up = static_cast<int>(i); up != kBase; up = parentOf[static_cast<size_t>(up)])
      above.push_back(static_cast<size_t>(up));
    for (const size_t k : above) {
      const JointSpec& a = s.joints[k];
      const Vec3 va = cross(a.axis, sub(link.pose.position, a.anchor));
      const Vec3 wa = rotate(conjugate(link.pose.orientation), a.axis);  // in the principal axes
      for (const size_t l : above) {
        const JointSpec& b = s.joints[l];
        const Vec3 vb = cross(b.axis, sub(link.pose.position, b.anchor));
        const Vec3 wb = rotate(conjugate(link.pose.orientation), b.axis);
        double rotational = 0;
        for (size_t d = 0; d < 3; ++d) rotational += link.inertia[d] * wa[d] * wb[d];
        m[k * n + l] += link.mass * dot(va, vb) + rotational;
      }
    }
  }
  return inverseDiagonal(std::move(m), n);
}

}  // namespace

WorldDef armWorldDef() {
  RobotPlacement placement;
  placement.name = "arm";
  placement.fixedBase = true;
  placement.jointPositions = kStartPose;
  RobotFiles files;
  files.sourceName = "arm7.urdf";
  const Expected<RobotModel> robot =
      loadRobot(std::string(rbsim::bench::kRobotsDir) + "/arm7.urdf", placement, files);
  if (!robot.ok()) fail(robot.error().message);
  WorldDef def;
  def.settings.dt = 1e-3;
  def.settings.gravity = rbsim::Vec3(0, 0, -9.81);
  def.settings.contact.enabled = false;
  def.settings.contact.sleeping = false;
  def.bodies = robot->bodies;
  for (BodyDef& body : def.bodies) body.collides = false;
  def.joints = robot->joints;
  for (NamedJointDef& joint : def.joints) {
    joint.def.damping = 0.0;
    joint.def.friction = 0.0;
    joint.def.limit.enabled = false;
    joint.def.actuatorLimits = {};
  }
  return def;
}

ArmScene armScene() {
  const WorldDef def = armWorldDef();
  const Expected<World> world = World::fromDef(def);
  if (!world.ok()) fail(world.error().message);
  ArmScene s;
  s.robot = "arm7";
  s.dt = def.settings.dt;
  s.gravity = plain(def.settings.gravity);
  // The links in the loader's order (parents first), the static base apart.
  std::map<std::string, int, std::less<>> linkIndex;
  std::string baseName;
  for (const BodyDef& body : def.bodies) {
    const BodyView view = world->body(world->findBody(body.name));
    if (body.isStatic) {
      baseName = body.name;
      s.base = poseOf(view);
      continue;
    }
    linkIndex[body.name] = static_cast<int>(s.links.size());
    s.links.push_back({body.name, view.mass(), plain(view.dynamics().inertiaBody), poseOf(view)});
  }
  std::vector<int> parentOf(s.links.size(), kBase);
  for (const NamedJointDef& joint : def.joints) {
    JointSpec j;
    j.name = joint.def.name;
    j.parent = joint.bodyA == baseName ? kBase : linkIndex.at(joint.bodyA);
    j.child = linkIndex.at(joint.bodyB);
    if (j.child != static_cast<int>(s.joints.size()))
      fail("joint " + j.name + " does not move the next link");
    j.anchor = plain(joint.def.anchor);
    j.axis = plain(joint.def.axis.normalized());
    j.position = joint.def.position;
    parentOf[static_cast<size_t>(j.child)] = j.parent;
    s.joints.push_back(j);
  }
  // Each joint's gains on the inertia it moves when the other joints are
  // free: 1 / (M⁻¹)_kk, with M the joint-space mass matrix of the start
  // pose. Not M_kk (the links beyond the joint turning as one body): an
  // explicit PD torque (Bullet's adapters, rbsim's --pd effort) is stable
  // only while dt times the largest eigenvalue of M⁻¹ K_d stays below 2,
  // and gains on M_kk put joint1's large damping on the small inertia of
  // joint1 and joint3 turning against each other (the arm then blows up
  // within a second of the sinusoids). On 1 / (M⁻¹)_kk the eigenvalues of
  // M⁻¹ K_d sum to n 2 ζ ω, which bounds the largest.
  const std::vector<double> mobility = inverseMassDiagonal(s, parentOf);
  const double omega = 2 * kPi * kNaturalFrequency;
  for (size_t k = 0; k < s.joints.size(); ++k) {
    const double inertia = 1 / mobility[k];
    s.joints[k].stiffness = inertia * omega * omega;
    s.joints[k].damping = 2 * kDampingRatio * inertia * omega;
  }
  for (size_t k = 0; k < s.joints.size(); ++k)
    s.frequencies.push_back(0.2 + 0.05 * static_cast<double>(k));
  return s;
}

}  // namespace rbsim::bench::robots
