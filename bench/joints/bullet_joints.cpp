// Bullet 3.24 on the joint scenes of joint_scenes.h:
//   nice -n 19 build/bench/joints/bench_joints_bullet --scene chain --reps 3
// btDiscreteDynamicsWorld + btSequentialImpulseConstraintSolver; ball joints
// are btPoint2PointConstraint, limited ball joints (ragdoll shoulders, hips,
// waist, neck) btConeTwistConstraint, hinges btHingeConstraint with setLimit.
// Built against the -float64 libraries when Debian ships them
// (bullet-float64.pc defines BT_USE_DOUBLE_PRECISION), so btScalar is double
// and the joint error is the solver's, not float rounding's; the label says
// which.
#include <btBulletDynamicsCommon.h>

#include "joint_scenes.h"

namespace {

namespace jb = rbsim::bench::joints;

#ifdef BT_USE_DOUBLE_PRECISION
constexpr const char* kLabel = "bullet-f64";
#else
constexpr const char* kLabel = "bullet-f32";
#endif

btVector3 toBt(const jb::Vec3& v) {
  return btVector3(static_cast<btScalar>(v[0]), static_cast<btScalar>(v[1]), static_cast<btScalar>(v[2]));
}

// A world frame at `origin` whose column `column` is `axis` (Bullet's hinge
// axis is the frame's z, the cone-twist axis its x).
btTransform frameAlong(const jb::Vec3& origin, const jb::Vec3& axis, int column) {
  const btVector3 a = toBt(axis).normalized();
  btVector3 u, v;
  btPlaneSpace1(a, u, v);  // u, v ⟂ a, right-handed (a, u, v)
  btMatrix3x3 basis;
  if (column == 2) {  // (u, v, a)
    basis.setValue(u.x(), v.x(), a.x(), u.y(), v.y(), a.y(), u.z(), v.z(), a.z());
  } else {  // (a, u, v)
    basis.setValue(a.x(), u.x(), v.x(), a.y(), u.y(), v.y(), a.z(), u.z(), v.z());
  }
  return btTransform(basis, toBt(origin));
}

class BulletEngine final : public jb::Engine {
 public:
  ~BulletEngine() override {
    // Constraints before bodies, bodies before the world's helpers.
    if (m_world) {
      for (auto& c : m_constraints) m_world->removeConstraint(c.get());
      for (auto& b : m_bodies) m_world->removeRigidBody(b.get());
      if (m_ground) m_world->removeRigidBody(m_ground.get());
    }
    m_constraints.clear();
    m_bodies.clear();
    m_ground.reset();
    m_world.reset();
  }

  void configure(const jb::Scene& s) override {
    m_config = std::make_unique<btDefaultCollisionConfiguration>();
    m_dispatcher = std::make_unique<btCollisionDispatcher>(m_config.get());
    m_broadphase = std::make_unique<btDbvtBroadphase>();
    m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    m_world = std::make_unique<btDiscreteDynamicsWorld>(m_dispatcher.get(), m_broadphase.get(), m_solver.get(),
                                                        m_config.get());
    m_world->setGravity(toBt(s.gravity));
    m_world->getSolverInfo().m_numIterations = s.velocityIterations;
    if (s.ground) {
      m_shapes.emplace_back(new btStaticPlaneShape(btVector3(0, 0, 1), 0));
      btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, m_shapes.back().get());
      info.m_friction = frictionPerObject();
      m_ground = std::make_unique<btRigidBody>(info);
      m_world->addRigidBody(m_ground.get());
    }
  }

  void addBody(const jb::BodySpec& b) override {
    btCollisionShape* shape;
    if (b.shape == jb::ShapeKind::kSphere) {
      shape = new btSphereShape(static_cast<btScalar>(b.radius));
    } else {
      auto* box = new btBoxShape(toBt(b.halfExtents));
      // The default 0.04 m margin lies inside the extents and is larger
      // than the thin chain links and ragdoll hands; keep it under half the
      // smallest half extent so the box keeps its size and a core.
      const double smallest = std::min({b.halfExtents[0], b.halfExtents[1], b.halfExtents[2]});
      box->setMargin(static_cast<btScalar>(std::min(0.04, 0.5 * smallest)));
      shape = box;
    }
    m_shapes.emplace_back(shape);
    btRigidBody::btRigidBodyConstructionInfo info(static_cast<btScalar>(b.mass), nullptr, shape, toBt(b.inertia));
    info.m_startWorldTransform.setOrigin(toBt(b.pose.position));
    const jb::Quat& q = b.pose.orientation;  // btQuaternion is (x, y, z, w)
    info.m_startWorldTransform.setRotation(btQuaternion(static_cast<btScalar>(q[1]), static_cast<btScalar>(q[2]),
                                                        static_cast<btScalar>(q[3]), static_cast<btScalar>(q[0])));
    info.m_friction = frictionPerObject();
    info.m_restitution = 0;
    m_bodies.emplace_back(new btRigidBody(info));
    btRigidBody* body = m_bodies.back().get();
    // No sleeping: every engine simulates every body for the whole run.
    body->setActivationState(DISABLE_DEACTIVATION);
    if (b.collides) {
      m_world->addRigidBody(body);
    } else {
      // In the broadphase (Bullet needs it) but colliding with nothing.
      m_world->addRigidBody(body, btBroadphaseProxy::DefaultFilter, 0);
    }
  }

  void addJoint(const jb::JointSpec& j) override {
    btRigidBody* a = m_bodies[static_cast<size_t>(j.bodyA)].get();
    btRigidBody* b = j.bodyB == jb::kWorld ? nullptr : m_bodies[static_cast<size_t>(j.bodyB)].get();
    const btTransform& ta = a->getWorldTransform();
    btTypedConstraint* c = nullptr;
    if (j.kind == jb::JointKind::kHinge) {
      const btTransform world = frameAlong(j.anchor, j.axis, 2);
      const btTransform inA = ta.inverse() * world;
      btHingeConstraint* hinge;
      if (b) {
        hinge = new btHingeConstraint(*a, *b, inA, b->getWorldTransform().inverse() * world);
      } else {
        hinge = new btHingeConstraint(*a, inA);
      }
      // Bullet's hinge angle is that of A relative to B (frame B's y seen
      // from frame A is at -θ when B turns by θ): negate the scene's limits.
      if (j.limited) hinge->setLimit(static_cast<btScalar>(-j.upper), static_cast<btScalar>(-j.lower));
      c = hinge;
    } else if (j.limited) {
      const btTransform world = frameAlong(j.anchor, j.axis, 0);
      const btTransform inA = ta.inverse() * world;
      btConeTwistConstraint* cone;
      if (b) {
        cone = new btConeTwistConstraint(*a, *b, inA, b->getWorldTransform().inverse() * world);
      } else {
        cone = new btConeTwistConstraint(*a, inA);
      }
      cone->setLimit(static_cast<btScalar>(j.swing), static_cast<btScalar>(j.swing), static_cast<btScalar>(j.twist));
      c = cone;
    } else {
      const btVector3 pivotA = ta.inverse() * toBt(j.anchor);
      if (b) {
        c = new btPoint2PointConstraint(*a, *b, pivotA, b->getWorldTransform().inverse() * toBt(j.anchor));
      } else {
        c = new btPoint2PointConstraint(*a, pivotA);
      }
    }
    m_constraints.emplace_back(c);
    // true: the two jointed bodies do not collide with each other.
    m_world->addConstraint(c, true);
  }

  void step(double dt) override {
    // maxSubSteps = 0: exactly one internal step of dt, no interpolation.
    m_world->stepSimulation(static_cast<btScalar>(dt), 0);
  }

  jb::Pose pose(int body) const override {
    const btTransform& t = m_bodies[static_cast<size_t>(body)]->getWorldTransform();
    const btQuaternion q = t.getRotation();
    jb::Pose p;
    p.position = {t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z()};
    p.orientation = {q.w(), q.x(), q.y(), q.z()};
    return p;
  }

  std::string settings() const override {
    const btContactSolverInfo& si = m_world->getSolverInfo();
    char text[512];
    std::snprintf(text, sizeof text,
                  "btDiscreteDynamicsWorld+btDbvtBroadphase+btSequentialImpulseConstraintSolver iterations=%d "
                  "erp=%.2f (joints) erp2=%.2f splitImpulse=%d warmstarting=%.2f; stepSimulation(dt,0); "
                  "friction sqrt(0.5) per object (product -> 0.5); no deactivation; btScalar=%s",
                  si.m_numIterations, static_cast<double>(si.m_erp), static_cast<double>(si.m_erp2),
                  si.m_splitImpulse, static_cast<double>(si.m_warmstartingFactor),
                  sizeof(btScalar) == 8 ? "double" : "float");
    return text;
  }

 private:
  // Bullet multiplies the two objects' coefficients.
  static btScalar frictionPerObject() { return static_cast<btScalar>(std::sqrt(jb::kFriction)); }

  std::unique_ptr<btDefaultCollisionConfiguration> m_config;
  std::unique_ptr<btCollisionDispatcher> m_dispatcher;
  std::unique_ptr<btDbvtBroadphase> m_broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
  std::unique_ptr<btDiscreteDynamicsWorld> m_world;
  std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
  std::unique_ptr<btRigidBody> m_ground;
  std::vector<std::unique_ptr<btRigidBody>> m_bodies;
  std::vector<std::unique_ptr<btTypedConstraint>> m_constraints;
};

}  // namespace

int main(int argc, char** argv) {
  return jb::runMain(argc, argv, kLabel, std::to_string(btGetVersion()),
                     [] { return std::unique_ptr<jb::Engine>(new BulletEngine()); });
}
