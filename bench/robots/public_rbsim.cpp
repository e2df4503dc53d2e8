// rbsim on the public robots' scenes (public_scenes.h):
//   build/bench/robots/bench_robots_public [--scene NAME|all] [--steps N] [--reps R]
//       [--self-collision on|off] [--write-worlds DIR]
// Each scene is a world file (public_model.cpp writes it; --write-worlds
// saves them, for rbserver --config) read by rbsim's config loader and
// stepped with each driven joint's position drive (JointDef::drive: the
// spring and damper implicit in the step), its target set every cycle.
// --self-collision adds `self_collision: true|false` to the robot; a tree
// whose loader does not know the key yet collides every pair of links not
// joined by a joint, whatever is asked (the CFG line says so).
#include <cstdio>
#include <fstream>
#include <optional>

#include "public_model.h"
#include "rbsim/physics/world.h"

namespace {

namespace rb = rbsim::bench::robots;

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "rbsim: %s\n", message.c_str());
  std::exit(1);
}

class RbsimPublic final : public rb::PublicEngine {
 public:
  void build(const rb::PublicScene& s, const std::vector<rb::JointGains>& gains) override {
    rb::PublicWorld w = rb::loadPublicWorld(s, gains);
    m_note = w.note;
    rbsim::Expected<rbsim::World> world = rbsim::World::fromDef(w.def);
    if (!world.ok()) fail(world.error().message);
    m_world.emplace(std::move(*world));
    m_gains = gains;
    m_joints.clear();
    for (const std::string& name : s.joints) {
      const rbsim::JointId id = m_world->findJoint(s.robot + "/" + name);
      if (id.isNull()) fail("no joint " + s.robot + "/" + name);
      m_joints.push_back(id);
    }
  }

  void readJoints(std::vector<rb::JointReading>& out) override {
    for (size_t k = 0; k < m_joints.size(); ++k) {
      const rbsim::JointState state = m_world->jointState(m_joints[k]);
      out[k] = {state.position, state.rate};
    }
  }

  void actuate(const std::vector<double>& targets, const std::vector<double>&) override {
    for (size_t k = 0; k < m_joints.size(); ++k) {
      rbsim::JointDrive drive;
      drive.enabled = true;
      drive.target = targets[k];
      drive.stiffness = m_gains[k].stiffness;
      drive.damping = m_gains[k].damping;
      const rbsim::Expected<bool> done = m_world->setJointDrive(m_joints[k], drive);
      if (!done.ok()) fail(done.error().message);
    }
  }

  void step() override { m_world->step(); }
  int contactPoints() override { return m_world->contactPointCount(); }
  int bodyCount() const override { return static_cast<int>(m_world->bodyCount()); }
  bool nativeDrives() const override { return true; }

  std::string settings() const override {
    std::string text =
        "world file via rbsim's config loader (URDF, merge_fixed_links); PD as each joint's "
        "implicit position drive, target set every cycle; contact and sleeping at the world "
        "file's defaults";
    if (!m_note.empty()) text += "; NOTE " + m_note;
    return text;
  }

 private:
  std::optional<rbsim::World> m_world;
  std::vector<rb::JointGains> m_gains;
  std::vector<rbsim::JointId> m_joints;
  std::string m_note;
};

}  // namespace

int main(int argc, char** argv) {
  rb::PublicOptions o;
  if (!rb::parsePublicOptions(argc, argv, o)) return 2;
  if (!o.writeWorlds.empty()) {
    for (rb::PublicScene s : rb::publicScenes()) {
      if (o.selfCollision >= 0) s.selfCollision = o.selfCollision == 1;
      const std::string path = o.writeWorlds + "/" + s.name + ".yaml";
      std::ofstream(path) << rb::loadPublicWorld(s, rb::publicGains(s)).yaml;
      std::fprintf(stderr, "wrote %s\n", path.c_str());
    }
  }
  return rb::runPublic(
      o, "rbsim", "this tree", [] { return std::unique_ptr<rb::PublicEngine>(new RbsimPublic()); },
      rb::publicGains);
}
