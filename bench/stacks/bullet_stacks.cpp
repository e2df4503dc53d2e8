// Bullet 3.24 on the stacking scenes of stack_scenes.h:
//   taskset -c 1 build/bench/stacks/bench_stacks_bullet --scene pyramid --n 90 --reps 3
// btDiscreteDynamicsWorld + btDbvtBroadphase + btSequentialImpulseConstraintSolver
// with Bullet's defaults (10 iterations unless --iters, split impulse, warm
// starting), as the anchors harness runs it. Built against the -float64
// libraries when Debian ships them (bullet-float64.pc defines
// BT_USE_DOUBLE_PRECISION), so that an 18 m tall pyramid's drift is the
// solver's, not float rounding's; the label says which.
#include <btBulletDynamicsCommon.h>

#include "stack_scenes.h"

namespace {

namespace sb = rbsim::bench::stacks;

#ifdef BT_USE_DOUBLE_PRECISION
constexpr const char* kLabel = "bullet-f64";
#else
constexpr const char* kLabel = "bullet-f32";
#endif

btScalar scalar(double v) { return static_cast<btScalar>(v); }
btVector3 toBt(const sb::Vec3& v) { return btVector3(scalar(v[0]), scalar(v[1]), scalar(v[2])); }

class BulletEngine final : public sb::Engine {
 public:
  ~BulletEngine() override {
    // Bodies out of the world before the world and its helpers go.
    if (m_world) {
      for (auto& b : m_bodies) m_world->removeRigidBody(b.get());
      if (m_ground) m_world->removeRigidBody(m_ground.get());
    }
    m_bodies.clear();
    m_ground.reset();
    m_world.reset();
  }

  void build(const sb::Scene& s, const sb::EngineSettings& settings) override {
    m_config = std::make_unique<btDefaultCollisionConfiguration>();
    m_dispatcher = std::make_unique<btCollisionDispatcher>(m_config.get());
    m_broadphase = std::make_unique<btDbvtBroadphase>();
    m_solver = std::make_unique<btSequentialImpulseConstraintSolver>();
    m_world = std::make_unique<btDiscreteDynamicsWorld>(m_dispatcher.get(), m_broadphase.get(), m_solver.get(),
                                                        m_config.get());
    m_world->setGravity(btVector3(0, 0, scalar(s.gravity)));
    if (settings.iterations > 0) m_world->getSolverInfo().m_numIterations = settings.iterations;
    m_sleep = settings.sleep;
    m_dt = s.dt;

    m_groundShape = std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0);
    btRigidBody::btRigidBodyConstructionInfo groundInfo(0, nullptr, m_groundShape.get());
    groundInfo.m_friction = frictionPerObject();
    groundInfo.m_restitution = scalar(sb::kRestitution);
    m_ground = std::make_unique<btRigidBody>(groundInfo);
    m_world->addRigidBody(m_ground.get());

    // One shared box shape (Bullet's advice for many equal bodies); its
    // default 0.04 m collision margin lies inside the 0.1 m half extents,
    // as in the anchors harness.
    m_boxShape = std::make_unique<btBoxShape>(btVector3(scalar(sb::kBoxHalf), scalar(sb::kBoxHalf), scalar(sb::kBoxHalf)));
    m_bodies.reserve(s.bodies.size());
    for (const sb::BodySpec& b : s.bodies) {
      const btScalar moment = scalar(b.inertia);
      btRigidBody::btRigidBodyConstructionInfo info(scalar(b.mass), nullptr, m_boxShape.get(),
                                                    btVector3(moment, moment, moment));
      info.m_startWorldTransform.setIdentity();
      info.m_startWorldTransform.setOrigin(toBt(b.position));
      const sb::Quat& q = b.orientation;  // btQuaternion is (x, y, z, w)
      info.m_startWorldTransform.setRotation(btQuaternion(scalar(q[1]), scalar(q[2]), scalar(q[3]), scalar(q[0])));
      info.m_friction = frictionPerObject();
      info.m_restitution = scalar(sb::kRestitution);
      m_bodies.emplace_back(new btRigidBody(info));
      btRigidBody* body = m_bodies.back().get();
      if (!m_sleep) body->setActivationState(DISABLE_DEACTIVATION);
      m_world->addRigidBody(body);
    }
  }

  void step() override {
    // maxSubSteps = 0: exactly one internal step of dt, no interpolation.
    m_world->stepSimulation(scalar(m_dt), 0);
  }

  sb::BodyState state(int body) const override {
    const btRigidBody* b = m_bodies[static_cast<size_t>(body)].get();
    const btVector3& p = b->getWorldTransform().getOrigin();
    const btVector3& v = b->getLinearVelocity();
    const btVector3& w = b->getAngularVelocity();
    sb::BodyState result;
    result.position = {p.x(), p.y(), p.z()};
    result.velocity = {v.x(), v.y(), v.z()};
    result.angularVelocity = {w.x(), w.y(), w.z()};
    return result;
  }

  long contacts() const override {
    long points = 0;
    for (int i = 0; i < m_dispatcher->getNumManifolds(); ++i) {
      points += m_dispatcher->getManifoldByIndexInternal(i)->getNumContacts();
    }
    return points;
  }

  std::string settings() const override {
    const btContactSolverInfo& si = m_world->getSolverInfo();
    char text[640];
    std::snprintf(text, sizeof text,
                  "btDiscreteDynamicsWorld+btDbvtBroadphase+btSequentialImpulseConstraintSolver iterations=%d "
                  "erp=%.2f erp2=%.2f splitImpulse=%d splitImpulsePenetrationThreshold=%.3f warmstarting=%.2f "
                  "solverMode=0x%x; stepSimulation(dt,0); friction sqrt(0.5) per object (product -> 0.5); "
                  "box margin 0.04 (inside extents); deactivation(sleeping)=%s; btScalar=%s",
                  si.m_numIterations, static_cast<double>(si.m_erp), static_cast<double>(si.m_erp2),
                  si.m_splitImpulse, static_cast<double>(si.m_splitImpulsePenetrationThreshold),
                  static_cast<double>(si.m_warmstartingFactor), static_cast<unsigned>(si.m_solverMode),
                  m_sleep ? "on" : "off", sizeof(btScalar) == 8 ? "double" : "float");
    return text;
  }

  std::string notes() const override {
    if (!m_sleep) return "";
    long sleeping = 0;
    for (const auto& b : m_bodies) sleeping += b->getActivationState() == ISLAND_SLEEPING ? 1 : 0;
    return "sleeping bodies at end: " + std::to_string(sleeping);
  }

 private:
  // Bullet multiplies the two objects' coefficients.
  static btScalar frictionPerObject() { return scalar(std::sqrt(sb::kFriction)); }

  std::unique_ptr<btDefaultCollisionConfiguration> m_config;
  std::unique_ptr<btCollisionDispatcher> m_dispatcher;
  std::unique_ptr<btDbvtBroadphase> m_broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
  std::unique_ptr<btDiscreteDynamicsWorld> m_world;
  std::unique_ptr<btCollisionShape> m_groundShape, m_boxShape;
  std::unique_ptr<btRigidBody> m_ground;
  std::vector<std::unique_ptr<btRigidBody>> m_bodies;
  double m_dt = 1e-3;
  bool m_sleep = false;
};

}  // namespace

int main(int argc, char** argv) {
  return sb::runMain(argc, argv, kLabel, true, std::to_string(btGetVersion()),
                     [] { return std::unique_ptr<sb::Engine>(new BulletEngine()); });
}
