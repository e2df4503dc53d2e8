// Bullet 3.24's rigid bodies and hinge constraints on the arm benchmark
// (arm_bench.h):
//   build/bench/robots/bench_robots_bullet_hinges [--reps 3]
// Each link a btRigidBody (centre of mass, principal inertia), the base a
// static one, each joint a btHingeConstraint between them (maximal
// coordinates: the solver closes the joints as far as its iterations and
// ERP take it), in a btDiscreteDynamicsWorld with the
// btSequentialImpulseConstraintSolver at its defaults (10 iterations, ERP
// 0.2), stepped by stepSimulation(dt, 0). The PD law's torque is applied as
// a couple on the two bodies about the hinge's axis every cycle (a hinge
// motor is a velocity target, not a spring of given stiffness). The joint
// readings come from the bodies (hingeReading). No collisions, no
// deactivation.
#include "arm_model.h"
#include "bullet_convert.h"

namespace {

namespace rb = rbsim::bench::robots;

// A world frame at `origin` whose z is `axis` (Bullet's hinge axis).
btTransform frameAlong(const rb::Vec3& origin, const rb::Vec3& axis) {
  const btVector3 a = rb::toBt(axis).normalized();
  btVector3 u, v;
  btPlaneSpace1(a, u, v);  // u, v ⟂ a, right-handed (a, u, v)
  btMatrix3x3 basis;
  basis.setValue(u.x(), v.x(), a.x(), u.y(), v.y(), a.y(), u.z(), v.z(),
                 a.z());  // columns (u, v, a)
  return btTransform(basis, rb::toBt(origin));
}

class HingeArm final : public rb::ArmEngine {
 public:
  ~HingeArm() override {
    if (m_world) {
      for (auto& c : m_hinges) m_world->removeConstraint(c.get());
      for (auto& b : m_links) m_world->removeRigidBody(b.get());
      if (m_base) m_world->removeRigidBody(m_base.get());
    }
    m_hinges.clear();
    m_links.clear();
    m_base.reset();
    m_world.reset();
  }

  void build(const rb::ArmScene& s) override {
    m_scene = &s;
    m_config = std::make_unique<btDefaultCollisionConfiguration>();
    m_dispatcher = std::make_unique<btCollisionDispatcher>(m_config.get());
    m_broadphase = std::make_unique<btDbvtBroadphase>();
    m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    m_world = std::make_unique<btDiscreteDynamicsWorld>(m_dispatcher.get(), m_broadphase.get(),
                                                        m_solver.get(), m_config.get());
    m_world->setGravity(rb::toBt(s.gravity));
    // Bullet wants a shape on every body; it only fills the broadphase
    // (the bodies collide with nothing, and the inertia is given).
    m_marker = std::make_unique<btSphereShape>(btScalar(0.01));
    btRigidBody::btRigidBodyConstructionInfo baseInfo(0, nullptr, m_marker.get());
    baseInfo.m_startWorldTransform = rb::toBt(s.base);
    m_base = std::make_unique<btRigidBody>(baseInfo);
    m_world->addRigidBody(m_base.get(), btBroadphaseProxy::StaticFilter, 0);
    for (const rb::LinkSpec& link : s.links) {
      btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(link.mass), nullptr,
                                                    m_marker.get(), rb::toBt(link.inertia));
      info.m_startWorldTransform = rb::toBt(link.pose);
      m_links.push_back(std::make_unique<btRigidBody>(info));
      m_links.back()->setActivationState(DISABLE_DEACTIVATION);
      m_world->addRigidBody(m_links.back().get(), btBroadphaseProxy::DefaultFilter, 0);
    }
    m_start.clear();
    m_axisInParent.clear();
    for (const rb::JointSpec& j : s.joints) {
      btRigidBody& parent = body(j.parent);
      btRigidBody& child = body(j.child);
      const btTransform world = frameAlong(j.anchor, j.axis);
      m_hinges.push_back(std::make_unique<btHingeConstraint>(
          parent, child, parent.getWorldTransform().inverse() * world,
          child.getWorldTransform().inverse() * world));
      m_world->addConstraint(m_hinges.back().get(), true);
      const rb::Quat parentStart = pose(j.parent).orientation;
      m_start.push_back(rb::multiply(rb::conjugate(parentStart), pose(j.child).orientation));
      m_axisInParent.push_back(rb::rotate(rb::conjugate(parentStart), j.axis));
    }
  }

  void readJoints(std::vector<rb::JointReading>& out) override {
    for (size_t k = 0; k < out.size(); ++k) {
      const rb::JointSpec& j = m_scene->joints[k];
      out[k] = rb::hingeReading(j.position, pose(j.parent).orientation, pose(j.child).orientation,
                                m_start[k], m_axisInParent[k],
                                rb::fromBt(body(j.parent).getAngularVelocity()),
                                rb::fromBt(body(j.child).getAngularVelocity()));
    }
  }

  void actuate(const std::vector<double>&, const std::vector<double>& torques) override {
    for (size_t k = 0; k < torques.size(); ++k) {
      const rb::JointSpec& j = m_scene->joints[k];
      // The axis as the parent carries it now; the torque on the child, its
      // reaction on the parent.
      const btVector3 couple = rb::toBt(rb::rotate(pose(j.parent).orientation, m_axisInParent[k])) *
                               static_cast<btScalar>(torques[k]);
      body(j.child).applyTorque(couple);
      if (j.parent != rb::kBase) body(j.parent).applyTorque(-couple);
    }
  }

  void step() override { m_world->stepSimulation(static_cast<btScalar>(m_scene->dt), 0); }

  rb::Pose linkPose(int link) override { return pose(link); }

  std::string settings() const override {
    const btContactSolverInfo& si = m_world->getSolverInfo();
    char text[320];
    std::snprintf(
        text, sizeof text,
        "btRigidBody "
        "links+btHingeConstraint+btDiscreteDynamicsWorld+btSequentialImpulseConstraintSolver "
        "iterations=%d erp=%.2f; stepSimulation(dt,0); PD as applyTorque couples; no deactivation; "
        "btScalar=%s",
        si.m_numIterations, static_cast<double>(si.m_erp),
        sizeof(btScalar) == 8 ? "double" : "float");
    return text;
  }

 private:
  btRigidBody& body(int index) const {
    return index == rb::kBase ? *m_base : *m_links[static_cast<size_t>(index)];
  }

  rb::Pose pose(int index) const {
    const btTransform& t = body(index).getWorldTransform();
    return {rb::fromBt(t.getOrigin()), rb::fromBt(t.getRotation())};
  }

  const rb::ArmScene* m_scene = nullptr;
  std::unique_ptr<btDefaultCollisionConfiguration> m_config;
  std::unique_ptr<btCollisionDispatcher> m_dispatcher;
  std::unique_ptr<btDbvtBroadphase> m_broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
  std::unique_ptr<btDiscreteDynamicsWorld> m_world;
  std::unique_ptr<btCollisionShape> m_marker;
  std::unique_ptr<btRigidBody> m_base;
  std::vector<std::unique_ptr<btRigidBody>> m_links;
  std::vector<std::unique_ptr<btHingeConstraint>> m_hinges;
  std::vector<rb::Quat> m_start;  // the child's orientation relative to the parent's at the start
  std::vector<rb::Vec3> m_axisInParent;  // each hinge's axis in its parent's frame
};

}  // namespace

int main(int argc, char** argv) {
  rb::Options o;
  if (!rb::parseOptions(argc, argv, o, "")) return 2;
  return rb::runMain(o, rb::armScene(), std::string("bullet-hinges-") + rb::kBulletPrecision,
                     std::to_string(btGetVersion()),
                     [] { return std::unique_ptr<rb::ArmEngine>(new HingeArm()); });
}
