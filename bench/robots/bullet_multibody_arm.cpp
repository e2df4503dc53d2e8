// Bullet 3.24's Featherstone multibody on the arm benchmark (arm_bench.h):
//   build/bench/robots/bench_robots_bullet_multibody [--reps 3]
// The arm as one btMultiBody with a fixed base and a revolute link per joint
// (reduced coordinates: the joints cannot open), in a
// btMultiBodyDynamicsWorld with btMultiBodyConstraintSolver, stepped by
// stepSimulation(dt, 0) (exactly one internal step). The PD law's torque is
// applied as the joint torque (addJointTorque) every cycle: Bullet's
// btMultiBodyJointMotor is a velocity constraint with an ERP-like gain, not
// a spring of given stiffness, so it could not be given the same law.
// btMultiBody's default damping of links (0.04) is turned off: rbsim and the
// rigid bodies have none. No colliders: nothing collides.
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>

#include "arm_model.h"
#include "bullet_convert.h"

namespace {

namespace rb = rbsim::bench::robots;

class MultiBodyArm final : public rb::ArmEngine {
 public:
  ~MultiBodyArm() override {
    if (m_world && m_body) m_world->removeMultiBody(m_body.get());
    m_body.reset();
    m_world.reset();
  }

  void build(const rb::ArmScene& s) override {
    m_scene = &s;
    m_config = std::make_unique<btDefaultCollisionConfiguration>();
    m_dispatcher = std::make_unique<btCollisionDispatcher>(m_config.get());
    m_broadphase = std::make_unique<btDbvtBroadphase>();
    m_solver = std::make_unique<btMultiBodyConstraintSolver>();
    m_world = std::make_unique<btMultiBodyDynamicsWorld>(m_dispatcher.get(), m_broadphase.get(),
                                                         m_solver.get(), m_config.get());
    m_world->setGravity(rb::toBt(s.gravity));
    // A fixed base: its mass and inertia take no part.
    m_body = std::make_unique<btMultiBody>(static_cast<int>(s.links.size()), btScalar(1),
                                           btVector3(1, 1, 1), true, false);
    m_body->setBasePos(rb::toBt(s.base.position));
    m_body->setWorldToBaseRot(rb::toBt(s.base.orientation).inverse());
    // Each link's frame is its centre of mass along its principal axes, as
    // in the scene; its joint's zero is the start pose (the scene's
    // coordinate is JointSpec::position plus Bullet's).
    for (const rb::JointSpec& j : s.joints) {
      const rb::LinkSpec& link = s.links[static_cast<size_t>(j.child)];
      const rb::Pose& parent =
          j.parent == rb::kBase ? s.base : s.links[static_cast<size_t>(j.parent)].pose;
      const rb::Quat toLink = rb::conjugate(link.pose.orientation);
      m_body->setupRevolute(
          j.child, static_cast<btScalar>(link.mass), rb::toBt(link.inertia),
          j.parent == rb::kBase ? -1 : j.parent,
          rb::toBt(rb::multiply(toLink, parent.orientation)),  // parent frame -> link frame
          rb::toBt(rb::rotate(toLink, j.axis)),
          rb::toBt(
              rb::rotate(rb::conjugate(parent.orientation), rb::sub(j.anchor, parent.position))),
          rb::toBt(rb::rotate(toLink, rb::sub(link.pose.position, j.anchor))), true);
    }
    m_body->finalizeMultiDof();
    m_body->setLinearDamping(0);
    m_body->setAngularDamping(0);
    m_body->setCanSleep(false);
    m_world->addMultiBody(m_body.get());
    m_posesOfStep = -1;
  }

  void readJoints(std::vector<rb::JointReading>& out) override {
    for (size_t k = 0; k < out.size(); ++k) {
      const int i = static_cast<int>(k);
      out[k] = {m_scene->joints[k].position + m_body->getJointPos(i), m_body->getJointVel(i)};
    }
  }

  void actuate(const std::vector<double>&, const std::vector<double>& torques) override {
    for (size_t k = 0; k < torques.size(); ++k)
      m_body->addJointTorque(static_cast<int>(k), static_cast<btScalar>(torques[k]));
  }

  void step() override {
    m_world->stepSimulation(static_cast<btScalar>(m_scene->dt), 0);
    ++m_step;
  }

  rb::Pose linkPose(int link) override {
    if (m_posesOfStep != m_step) {
      // The links' frames from the joint positions (outside the timed
      // region): index 0 is the base, k + 1 link k.
      m_body->forwardKinematics(m_worldToLocal, m_origins);
      m_posesOfStep = m_step;
    }
    const size_t i = static_cast<size_t>(link) + 1;
    return {rb::fromBt(m_origins[static_cast<int>(i)]),
            rb::fromBt(m_worldToLocal[static_cast<int>(i)].inverse())};
  }

  std::string settings() const override {
    const btContactSolverInfo& si = m_world->getSolverInfo();
    char text[320];
    std::snprintf(
        text, sizeof text,
        "btMultiBody (fixed base, revolute links, gyro term on, no link "
        "damping)+btMultiBodyDynamicsWorld+"
        "btMultiBodyConstraintSolver iterations=%d; stepSimulation(dt,0); PD as addJointTorque; "
        "btScalar=%s",
        si.m_numIterations, sizeof(btScalar) == 8 ? "double" : "float");
    return text;
  }

 private:
  const rb::ArmScene* m_scene = nullptr;
  std::unique_ptr<btDefaultCollisionConfiguration> m_config;
  std::unique_ptr<btCollisionDispatcher> m_dispatcher;
  std::unique_ptr<btDbvtBroadphase> m_broadphase;
  std::unique_ptr<btMultiBodyConstraintSolver> m_solver;
  std::unique_ptr<btMultiBodyDynamicsWorld> m_world;
  std::unique_ptr<btMultiBody> m_body;
  btAlignedObjectArray<btQuaternion> m_worldToLocal;
  btAlignedObjectArray<btVector3> m_origins;
  long m_step = 0, m_posesOfStep = -1;
};

}  // namespace

int main(int argc, char** argv) {
  rb::Options o;
  if (!rb::parseOptions(argc, argv, o, "")) return 2;
  return rb::runMain(o, rb::armScene(), std::string("bullet-multibody-") + rb::kBulletPrecision,
                     std::to_string(btGetVersion()),
                     [] { return std::unique_ptr<rb::ArmEngine>(new MultiBodyArm()); });
}
