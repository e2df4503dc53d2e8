// ODE 0.16 (Debian's double-precision build) on the joint scenes of
// joint_scenes.h:
//   nice -n 19 build/bench/joints/bench_joints_ode --scene grid --reps 3
// dWorldQuickStep with the scene's iteration count (10); ball joints are
// dJointCreateBall, hinges dJointCreateHinge with dParamLoStop/HiStop.
// ERP 0.2 and CFM 1e-10 (the double-precision build's default) are ODE's
// defaults, kept for joints and contacts alike: ODE has no separate joint
// ERP; 0.2 corrects a fifth of the joint drift per step, and a CFM this
// small leaves the joints practically rigid, as in the other engines.
//
// Not supported here: cone/twist limits on ball joints. ODE has none on
// dJointBall; they would need a ball + angular motor (dAMotorEuler) pair,
// which no longer costs the same as one joint, so the ragdoll's shoulders,
// hips, waist and neck are unlimited ball joints (the notes say so).
//
// One timed step = dSpaceCollide + dWorldQuickStep + dJointGroupEmpty (the
// contact joints), i.e. what the other engines do inside their step.
#include <ode/ode.h>

#include "joint_scenes.h"

#ifndef ODE_PKG_VERSION
#define ODE_PKG_VERSION "unknown"
#endif

namespace {

namespace jb = rbsim::bench::joints;

constexpr int kMaxContactsPerPair = 8;   // box–box returns up to 8
constexpr double kSurfaceLayer = 0.001;  // m, the manual's remedy for contact jitter

class OdeEngine final : public jb::Engine {
 public:
  ~OdeEngine() override {
    if (m_contactGroup) dJointGroupDestroy(m_contactGroup);
    if (m_space) dSpaceDestroy(m_space);  // destroys its geoms
    if (m_world) dWorldDestroy(m_world);  // destroys bodies and joints
  }

  void configure(const jb::Scene& s) override {
    // QuickStep shuffles constraints with ODE's global RNG: reseed it so
    // that every rep in a process is the same simulation.
    dRandSetSeed(0);
    m_world = dWorldCreate();
    m_space = dHashSpaceCreate(nullptr);
    m_contactGroup = dJointGroupCreate(0);
    dWorldSetGravity(m_world, s.gravity[0], s.gravity[1], s.gravity[2]);
    dWorldSetQuickStepNumIterations(m_world, s.velocityIterations);
    dWorldSetContactSurfaceLayer(m_world, kSurfaceLayer);
    m_contacts = s.contacts;
    if (s.ground) dCreatePlane(m_space, 0, 0, 1, 0);
  }

  void addBody(const jb::BodySpec& b) override {
    dBodyID body = dBodyCreate(m_world);
    dMass mass;
    dMassSetParameters(&mass, b.mass, 0, 0, 0, b.inertia[0], b.inertia[1], b.inertia[2], 0, 0, 0);
    dBodySetMass(body, &mass);
    dBodySetPosition(body, b.pose.position[0], b.pose.position[1], b.pose.position[2]);
    const dQuaternion q = {b.pose.orientation[0], b.pose.orientation[1], b.pose.orientation[2],
                           b.pose.orientation[3]};  // ODE's order is (w, x, y, z) too
    dBodySetQuaternion(body, q);
    // Without a geom a body takes part in no collision at all.
    if (m_contacts && b.collides) {
      dGeomID geom = b.shape == jb::ShapeKind::kSphere
                         ? dCreateSphere(m_space, b.radius)
                         : dCreateBox(m_space, 2 * b.halfExtents[0], 2 * b.halfExtents[1], 2 * b.halfExtents[2]);
      dGeomSetBody(geom, body);
    }
    m_bodies.push_back(body);
  }

  void addJoint(const jb::JointSpec& j) override {
    dBodyID a = m_bodies[static_cast<size_t>(j.bodyA)];
    dBodyID b = j.bodyB == jb::kWorld ? nullptr : m_bodies[static_cast<size_t>(j.bodyB)];
    dJointID joint;
    if (j.kind == jb::JointKind::kHinge) {
      joint = dJointCreateHinge(m_world, nullptr);
      dJointAttach(joint, a, b);
      dJointSetHingeAnchor(joint, j.anchor[0], j.anchor[1], j.anchor[2]);
      // Setting the axis records the current relative orientation as angle 0.
      dJointSetHingeAxis(joint, j.axis[0], j.axis[1], j.axis[2]);
      if (j.limited) {
        // ODE's hinge angle is that of body 1 (A) relative to body 2 (B):
        // negate the scene's limits (B relative to A).
        dJointSetHingeParam(joint, dParamLoStop, -j.upper);
        dJointSetHingeParam(joint, dParamHiStop, -j.lower);
      }
    } else {
      joint = dJointCreateBall(m_world, nullptr);
      dJointAttach(joint, a, b);
      dJointSetBallAnchor(joint, j.anchor[0], j.anchor[1], j.anchor[2]);
      if (j.limited) m_unlimitedBalls++;
    }
  }

  void step(double dt) override {
    if (m_contacts) dSpaceCollide(m_space, this, &nearCallback);
    dWorldQuickStep(m_world, dt);
    if (m_contacts) dJointGroupEmpty(m_contactGroup);
  }

  jb::Pose pose(int body) const override {
    const dBodyID b = m_bodies[static_cast<size_t>(body)];
    const dReal* p = dBodyGetPosition(b);
    const dReal* q = dBodyGetQuaternion(b);
    jb::Pose result;
    result.position = {p[0], p[1], p[2]};
    result.orientation = {q[0], q[1], q[2], q[3]};
    return result;
  }

  std::string settings() const override {
    char text[512];
    std::snprintf(text, sizeof text,
                  "dWorldQuickStep iterations=%d SOR=%.2f ERP=%.2f CFM=%.1e (defaults, joints and contacts); "
                  "dHashSpace, contacts dContactApprox1 mu=0.5 bounce=0 surfaceLayer=%.3f <=%d per pair, "
                  "jointed pairs skipped; autoDisable=off; %s",
                  dWorldGetQuickStepNumIterations(m_world), static_cast<double>(dWorldGetQuickStepW(m_world)),
                  static_cast<double>(dWorldGetERP(m_world)), static_cast<double>(dWorldGetCFM(m_world)),
                  kSurfaceLayer, kMaxContactsPerPair, dGetConfiguration());
    return text;
  }

  std::string notes() const override {
    if (m_unlimitedBalls == 0) return "";
    return std::to_string(m_unlimitedBalls) + " cone/twist-limited ball joints simulated without limits "
           "(dJointBall has none)";
  }

 private:
  static void nearCallback(void* data, dGeomID g1, dGeomID g2) {
    auto* self = static_cast<OdeEngine*>(data);
    dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
    // Jointed bodies do not collide (as Bullet's addConstraint(c, true)).
    if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact)) return;
    dContact contact[kMaxContactsPerPair];
    const int n = dCollide(g1, g2, kMaxContactsPerPair, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
      contact[i].surface.mode = dContactApprox1;  // friction pyramid with mu as a coefficient
      contact[i].surface.mu = jb::kFriction;
      contact[i].surface.bounce = 0;
      dJointID joint = dJointCreateContact(self->m_world, self->m_contactGroup, &contact[i]);
      dJointAttach(joint, b1, b2);
    }
  }

  dWorldID m_world = nullptr;
  dSpaceID m_space = nullptr;
  dJointGroupID m_contactGroup = nullptr;
  std::vector<dBodyID> m_bodies;
  bool m_contacts = false;
  int m_unlimitedBalls = 0;
};

}  // namespace

int main(int argc, char** argv) {
  dInitODE2(0);
  dAllocateODEDataForThread(dAllocateMaskAll);
  const int rc = jb::runMain(argc, argv, "ode", ODE_PKG_VERSION,
                             [] { return std::unique_ptr<jb::Engine>(new OdeEngine()); });
  dCloseODE();
  return rc;
}
