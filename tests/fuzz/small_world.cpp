#include "small_world.h"

#include <cstdio>
#include <cstdlib>

namespace rbsim::fuzz {
namespace {

World buildSmallWorld() {
  WorldSettings settings;
  settings.dt = 0.01;  // coarse: more happens per step, and steps are cheap
  World world(settings);
  const auto add = [&](const char* name, Shape shape, const Vec3& position, bool isStatic) {
    BodyDef def;
    def.name = name;
    def.shape = std::move(shape);
    def.position = position;
    def.isStatic = isStatic;
    if (!world.createBody(def)) {
      std::fprintf(stderr, "rbsim fuzz: the small world cannot create '%s'\n", name);
      std::abort();
    }
  };
  add("ground", PlaneShape{}, Vec3::Zero(), true);
  add("crate", BoxShape{Vec3(0.2, 0.3, 0.1)}, Vec3(0, 0, 0.1), false);
  add("ball", SphereShape{0.1}, Vec3(0, 0, 0.3), false);
  add("pill", CapsuleShape{0.05, 0.2}, Vec3(1, 0, 0.05), false);
  add("drum", CylinderShape{0.1, 0.1}, Vec3(-1, 0, 1), false);
  return world;
}

}  // namespace

const World& smallWorld() {
  static const World world = buildSmallWorld();
  return world;
}

}  // namespace rbsim::fuzz
