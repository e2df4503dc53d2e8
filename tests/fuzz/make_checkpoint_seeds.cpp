// Writes the seed corpus of fuzz_checkpoint (tests/fuzz/corpus/checkpoint/):
// checkpoint payloads of sessions of the small world, with spawned bodies
// of every shape, one with its own collision group and mask, a pair
// excluded from collision, wrenches pending and acting, contacts in the
// solver's warm-start cache, and joints of every kind. Run after the checkpoint format changes:
//
//   build/tests/fuzz/fuzz_make_checkpoint_seeds tests/fuzz/corpus/checkpoint

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "config/config_loader.h"
#include "fuzz_paths.h"
#include "persist/session_checkpoint.h"
#include "session/session.h"
#include "small_world.h"

namespace {

using namespace rbsim;

bool save(const Session& session, const std::filesystem::path& path) {
  const auto payload = encodeSessionCheckpoint(session);
  if (!payload) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), payload.error().message.c_str());
    return false;
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(payload->data()), static_cast<std::streamsize>(payload->size()));
  return static_cast<bool>(out);
}

WrenchRequest push(const char* body, WrenchMode mode, int64_t firstStep) {
  WrenchRequest request;
  request.client = "seed";
  request.body = body;
  request.force = Vec3(3, 0, 1);
  request.point = Vec3(0.05, 0, 0);
  request.mode = mode;
  request.durationSteps = 5;
  request.firstStep = firstStep;
  return request;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_DIRECTORY\n", argv[0]);
    return 2;
  }
  const std::filesystem::path directory(argv[1]);
  std::filesystem::create_directories(directory);

  Session fresh(fuzz::smallWorld());
  if (!save(fresh, directory / "fresh")) return 1;

  Session busy(fuzz::smallWorld());
  for (const char* yaml :
       {"{name: m, shape: {type: mesh, file: cube.obj}, position: [0, 0, 2]}",
        "{name: t, shape: {type: mesh, file: tetrahedron.stl}, position: [0, 1, 0.5]}",
        "{name: s, shape: {type: sphere, radius: 0.2}, position: [1, 1, 0.2], ccd: true}",
        "{name: v, shape: {type: box, half_extents: [0.1, 0.1, 0.1]}, position: [0, 0, 0.1], collides: false}",
        "{name: f, shape: {type: sphere, radius: 0.1}, position: [1, -1, 0.2], collision_group: 2, "
        "collision_mask: 0xFFFFFFFD}",
        "{name: g, shape: {type: box, half_extents: [0.2, 0.1, 0.01]}, position: [-1, 0, 0.3], "
        "mass: 2, center_of_mass: [0.05, 0, 0], inertia: [[0.01, -0.001, 0], [-0.001, 0.02, 0], "
        "[0, 0, 0.03]]}"}) {
    const auto def = parseBodyDef(yaml, "seed", rbsim::fuzz::kMeshDir);
    if (!def || !busy.world().createBody(*def)) {
      std::fprintf(stderr, "cannot spawn %s\n", yaml);
      return 1;
    }
  }
  // A pair excluded from collision (as a robot's links are).
  if (!busy.world().setPairCollision(busy.world().findBody("crate"), busy.world().findBody("ball"), false)) {
    std::fprintf(stderr, "cannot exclude crate-ball\n");
    return 1;
  }
  busy.wrenches().add(push("crate", WrenchMode::Persistent, 1));
  busy.wrenches().add(push("ball", WrenchMode::Duration, 1));
  busy.wrenches().add(push("pill", WrenchMode::OneStep, 40));
  WrenchRequest atBodyPoint = push("crate", WrenchMode::Persistent, 1);
  atBodyPoint.client = "seed-2";
  atBodyPoint.pointFrame = WrenchFrame::ShapeFrame;
  busy.wrenches().add(atBodyPoint);
  WrenchRequest bodyForce = push("m", WrenchMode::Duration, 30);
  bodyForce.frame = WrenchFrame::ShapeFrame;  // its world point is still pending
  busy.wrenches().add(bodyForce);
  for (int i = 0; i < 20; ++i) busy.step();
  busy.pause();
  busy.requestSteps(3);
  if (!save(busy, directory / "busy")) return 1;

  // Joints of every kind on the busy world's bodies, one of them removed
  // (a hole in the joint slot table), after a few steps.
  Session jointed(fuzz::smallWorld());
  World& world = jointed.world();
  const BodyId crate = world.findBody("crate"), ball = world.findBody("ball"), pill = world.findBody("pill");
  if (crate.isNull() || ball.isNull() || pill.isNull()) {
    std::fprintf(stderr, "the small world lacks crate, ball or pill\n");
    return 1;
  }
  const auto joint = [&](const char* name, JointType type, BodyId a, BodyId b, const Vec3& anchor) {
    JointDef def;
    def.name = name;
    def.type = type;
    def.bodyA = a;
    def.bodyB = b;
    def.anchor = anchor;
    def.axis = Vec3(0, 0, 1);
    return def;
  };
  JointDef hinge = joint("hinge", JointType::Revolute, BodyId{}, crate, world.body(crate).position() + Vec3(0, 0, 0.3));
  hinge.limit = {true, -0.4, 0.4};
  hinge.position = 0.1;  // made away from its zero, as a robot description places it
  hinge.drive.enabled = true;
  hinge.drive.target = 0.2;
  hinge.drive.stiffness = 50.0;
  hinge.damping = 0.1;
  hinge.friction = 0.05;
  JointDef rope = joint("rope", JointType::Distance, crate, ball, world.body(crate).position());
  rope.anchorB = world.body(ball).position();
  rope.limit = {true, 0.0, (rope.anchorB - rope.anchor).norm() + 0.2};
  JointDef cone = joint("cone", JointType::Spherical, BodyId{}, pill, world.body(pill).position() + Vec3(0, 0, 0.2));
  cone.coneAngle = 0.5;
  JointDef spare = joint("spare", JointType::Fixed, ball, pill, world.body(ball).position());
  for (const JointDef& def : {hinge, rope, cone, spare}) {
    if (!world.createJoint(def)) {
      std::fprintf(stderr, "cannot join %s\n", def.name.c_str());
      return 1;
    }
  }
  (void)world.removeJoint(world.findJoint("spare"));
  for (int i = 0; i < 20; ++i) jointed.step();
  JointCommandRequest later;  // scheduled ahead: it is in the checkpoint
  later.client = "seed";
  later.seq = 1;
  later.joint = "hinge";
  later.mode = JointCommandMode::Velocity;
  later.target = 1.0;
  later.maxEffort = 2.0;
  later.firstStep = 40;
  jointed.jointCommands().add(later);
  if (!save(jointed, directory / "jointed")) return 1;
  return 0;
}
