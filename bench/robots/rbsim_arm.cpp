// rbsim on the arm benchmark (arm_bench.h): config/robots/arm7.urdf as the
// loader makes it, stepped under PD position control:
//   build/bench/robots/bench_robots_rbsim [--pd drive|effort] [--reps 3]
// --pd drive (the default): each joint's position drive (JointDef::drive)
// with the PD law's gains, its target set every cycle; the spring and
// damper are implicit in rbsim's step. --pd effort: the harness's PD torque,
// worked out from the joint readings, applied as the joint's direct effort
// (explicit, as Bullet's adapters apply it).
#include <cstdio>
#include <optional>

#include "arm_model.h"
#include "rbsim/physics/world.h"

namespace {

namespace rb = rbsim::bench::robots;

class RbsimArm final : public rb::ArmEngine {
 public:
  explicit RbsimArm(bool drive) : m_drive(drive) {}

  void build(const rb::ArmScene& s) override {
    const rbsim::WorldDef def = rb::armWorldDef();
    rbsim::Expected<rbsim::World> world = rbsim::World::fromDef(def);
    if (!world.ok()) fail(world.error().message);
    m_world.emplace(std::move(*world));
    m_scene = &s;
    m_joints.clear();
    m_links.clear();
    for (const rb::JointSpec& j : s.joints) m_joints.push_back(m_world->findJoint(j.name));
    for (const rb::LinkSpec& l : s.links) m_links.push_back(m_world->findBody(l.name));
  }

  void readJoints(std::vector<rb::JointReading>& out) override {
    for (size_t k = 0; k < m_joints.size(); ++k) {
      const rbsim::JointState state = m_world->jointState(m_joints[k]);
      out[k] = {state.position, state.rate};
    }
  }

  void actuate(const std::vector<double>& targets, const std::vector<double>& torques) override {
    for (size_t k = 0; k < m_joints.size(); ++k) {
      const rb::JointSpec& j = m_scene->joints[k];
      if (m_drive) {
        rbsim::JointDrive drive;
        drive.enabled = true;
        drive.target = targets[k];
        drive.stiffness = j.stiffness;
        drive.damping = j.damping;
        check(m_world->setJointDrive(m_joints[k], drive));
      } else {
        check(m_world->setJointEffort(m_joints[k], torques[k]));
      }
    }
  }

  void step() override { m_world->step(); }

  rb::Pose linkPose(int link) override {
    const rbsim::BodyView b = m_world->body(m_links[static_cast<size_t>(link)]);
    const rbsim::Quaternion& q = b.orientation();
    return {{b.position().x(), b.position().y(), b.position().z()}, {q.w, q.x, q.y, q.z}};
  }

  std::string settings() const override {
    return std::string("URDF via rbsim's loader; joints at the position level (exact solve); PD ") +
           (m_drive ? "as each joint's implicit position drive, target set every cycle"
                    : "as explicit joint efforts from the readings") +
           "; no contacts, no sleeping";
  }

 private:
  [[noreturn]] static void fail(const std::string& message) {
    std::fprintf(stderr, "rbsim: %s\n", message.c_str());
    std::exit(1);
  }
  static void check(const rbsim::Expected<bool>& done) {
    if (!done.ok()) fail(done.error().message);
  }

  bool m_drive;
  std::optional<rbsim::World> m_world;
  const rb::ArmScene* m_scene = nullptr;
  std::vector<rbsim::JointId> m_joints;
  std::vector<rbsim::BodyId> m_links;
};

}  // namespace

int main(int argc, char** argv) {
  rb::Options o;
  if (!rb::parseOptions(argc, argv, o, "[--pd drive|effort]")) return 2;
  if (o.mode.empty()) o.mode = "drive";
  if (o.mode != "drive" && o.mode != "effort") {
    rb::usage(argv[0], "[--pd drive|effort]");
    return 2;
  }
  const bool drive = o.mode == "drive";
  return rb::runMain(o, rb::armScene(), drive ? "rbsim-drive" : "rbsim-effort", "this tree",
                     [drive] { return std::unique_ptr<rb::ArmEngine>(new RbsimArm(drive)); });
}
