// ODE 0.16 (Debian's double-precision build) on the stacking scenes of
// stack_scenes.h:
//   taskset -c 1 build/bench/stacks/bench_stacks_ode --scene pyramid --n 90 --reps 3
// Settings as the anchors harness runs ODE: dWorldQuickStep with its default
// 20 iterations (unless --iters), SOR 1.3, ERP 0.2, CFM 1e-10 (the
// double-precision build's defaults), contact surface layer 1 mm (the
// manual's remedy for resting-contact jitter), dContactApprox1 (friction
// pyramid, mu = 0.5), no bounce, up to 8 points per pair, a hash space,
// auto-disable off whatever --sleep says (the anchors' ODE never sleeps, so
// neither does this one: the label stays "ode").
//
// One timed step = dSpaceCollide + dWorldQuickStep + dJointGroupEmpty (the
// contact joints): what the other engines do inside their step.
#include <ode/ode.h>

#include "stack_scenes.h"

#ifndef ODE_PKG_VERSION
#define ODE_PKG_VERSION "unknown"
#endif

namespace {

namespace sb = rbsim::bench::stacks;

constexpr int kMaxContactsPerPair = 8;   // box–box returns up to 8
constexpr double kSurfaceLayer = 0.001;  // m

class OdeEngine final : public sb::Engine {
 public:
  ~OdeEngine() override {
    if (m_contactGroup) dJointGroupDestroy(m_contactGroup);
    if (m_space) dSpaceDestroy(m_space);  // destroys its geoms
    if (m_world) dWorldDestroy(m_world);  // destroys bodies and joints
  }

  void build(const sb::Scene& s, const sb::EngineSettings& settings) override {
    // QuickStep shuffles constraints with ODE's global RNG: reseed it so
    // that every rep in a process is the same simulation.
    dRandSetSeed(0);
    m_world = dWorldCreate();
    m_space = dHashSpaceCreate(nullptr);
    m_contactGroup = dJointGroupCreate(0);
    dWorldSetGravity(m_world, 0, 0, s.gravity);
    if (settings.iterations > 0) dWorldSetQuickStepNumIterations(m_world, settings.iterations);
    dWorldSetContactSurfaceLayer(m_world, kSurfaceLayer);
    dWorldSetAutoDisableFlag(m_world, 0);
    m_dt = s.dt;
    dCreatePlane(m_space, 0, 0, 1, 0);  // z = 0, normal +z, static
    m_bodies.reserve(s.bodies.size());
    for (const sb::BodySpec& b : s.bodies) {
      dBodyID body = dBodyCreate(m_world);
      dMass mass;
      dMassSetParameters(&mass, b.mass, 0, 0, 0, b.inertia, b.inertia, b.inertia, 0, 0, 0);
      dBodySetMass(body, &mass);
      dBodySetPosition(body, b.position[0], b.position[1], b.position[2]);
      const dQuaternion q = {b.orientation[0], b.orientation[1], b.orientation[2],
                             b.orientation[3]};  // ODE's order is (w, x, y, z) too
      dBodySetQuaternion(body, q);
      dGeomID geom = dCreateBox(m_space, 2 * b.half, 2 * b.half, 2 * b.half);
      dGeomSetBody(geom, body);
      m_bodies.push_back(body);
    }
  }

  void step() override {
    m_stepContacts = 0;
    dSpaceCollide(m_space, this, &nearCallback);
    dWorldQuickStep(m_world, m_dt);
    dJointGroupEmpty(m_contactGroup);
    m_contacts = m_stepContacts;
  }

  sb::BodyState state(int body) const override {
    const dBodyID b = m_bodies[static_cast<size_t>(body)];
    const dReal* p = dBodyGetPosition(b);
    const dReal* v = dBodyGetLinearVel(b);
    const dReal* w = dBodyGetAngularVel(b);
    sb::BodyState result;
    result.position = {p[0], p[1], p[2]};
    result.velocity = {v[0], v[1], v[2]};
    result.angularVelocity = {w[0], w[1], w[2]};
    return result;
  }

  // The contact joints made in the last step (ODE keeps none across steps).
  long contacts() const override { return m_contacts; }

  std::string settings() const override {
    char text[512];
    std::snprintf(text, sizeof text,
                  "dHashSpace + dWorldQuickStep iterations=%d SOR=%.2f ERP=%.2f CFM=%.1e surfaceLayer=%.3f "
                  "maxCorrectingVel=default(inf) autoDisable=off; contacts: dContactApprox1 mu=0.5 bounce=0, "
                  "<=%d per pair; %s",
                  dWorldGetQuickStepNumIterations(m_world), static_cast<double>(dWorldGetQuickStepW(m_world)),
                  static_cast<double>(dWorldGetERP(m_world)), static_cast<double>(dWorldGetCFM(m_world)),
                  kSurfaceLayer, kMaxContactsPerPair, dGetConfiguration());
    return text;
  }

 private:
  static void nearCallback(void* data, dGeomID g1, dGeomID g2) {
    auto* self = static_cast<OdeEngine*>(data);
    dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
    if (!b1 && !b2) return;  // static against static
    dContact contact[kMaxContactsPerPair];
    const int n = dCollide(g1, g2, kMaxContactsPerPair, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
      contact[i].surface.mode = dContactApprox1;  // friction pyramid with mu as a coefficient
      contact[i].surface.mu = sb::kFriction;
      contact[i].surface.bounce = sb::kRestitution;
      dJointID joint = dJointCreateContact(self->m_world, self->m_contactGroup, &contact[i]);
      dJointAttach(joint, b1, b2);
    }
    self->m_stepContacts += n;
  }

  dWorldID m_world = nullptr;
  dSpaceID m_space = nullptr;
  dJointGroupID m_contactGroup = nullptr;
  std::vector<dBodyID> m_bodies;
  double m_dt = 1e-3;
  long m_contacts = 0, m_stepContacts = 0;
};

}  // namespace

int main(int argc, char** argv) {
  dInitODE2(0);
  dAllocateODEDataForThread(dAllocateMaskAll);
  const int rc = sb::runMain(argc, argv, "ode", false, ODE_PKG_VERSION,
                             [] { return std::unique_ptr<sb::Engine>(new OdeEngine()); });
  dCloseODE();
  return rc;
}
