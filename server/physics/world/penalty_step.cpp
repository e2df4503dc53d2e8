// World stepping with the penalty model: spring–damper contact forces that
// are functions of the state, integrated by the world's integrator like
// gravity. Bodies that touch nothing take integrateFree; the bodies in
// contact are integrated together as one system, because their contact
// forces couple them: an RK4 stage of one body needs the other's stage state.
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "physics/body/body.h"
#include "physics/body/external_load.h"
#include "physics/body/integrator.h"
#include "physics/solver/contact_solver.h"
#include "physics/collision/collision_detector.h"
#include "physics/world/penalty_contact.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

namespace rbsim {

namespace {

// One moving body of the system, as it was at the step start.
struct SystemBody {
  RigidState start;
  Mat3 startRotation;
  BodyDynamics dynamics;
  ForceInputs inputs;  // gravity and the clients' load: never the contact forces
};

// Impulses of each contact point over the step (N·s), for the records.
struct PointImpulses {
  std::vector<double> normal;
  std::vector<Vec3> tangent;
};

class PenaltySystem {
 public:
  PenaltySystem(std::vector<SystemBody> bodies, std::vector<int> systemIndex,
                std::vector<BodyMotion> fixedMotion, std::vector<PenaltyPoint> points,
                PenaltyLaw law)
      : m_bodies(std::move(bodies)),
        m_systemIndex(std::move(systemIndex)),
        m_fixedMotion(std::move(fixedMotion)),
        m_points(std::move(points)),
        m_law(law) {
    m_impulses.normal.assign(m_points.size(), 0.0);
    m_impulses.tangent.assign(m_points.size(), Vec3::Zero());
  }

  // The states at the end of a step of h, in system order.
  std::vector<RigidState> step(IntegratorKind kind, double h);
  const PointImpulses& impulses() const { return m_impulses; }

 private:
  using States = std::vector<RigidState>;
  using Rotations = std::vector<Mat3>;

  const BodyMotion& motionOf(int dense, const std::vector<BodyMotion>& moving) const {
    const int j = m_systemIndex[static_cast<std::size_t>(dense)];
    return j >= 0 ? moving[static_cast<std::size_t>(j)]
                  : m_fixedMotion[static_cast<std::size_t>(dense)];
  }
  std::vector<BodyMotion> motions(const States& states, const Rotations& rotations) const;
  // Which points push at a state (the law's switch, see penaltyPushes), and
  // the two values whose sign changes are the switches: k d and k d + c ḋ
  // (N). They only guide the search for the moment of a switch; `pushing`
  // decides.
  struct Switches {
    std::vector<char> pushing;
    std::vector<double> springForce;  // k d
    std::vector<double> linearForce;  // k d + c ḋ
  };
  Switches switchesAt(const States& states, const Rotations& rotations) const;
  // The contact wrench on every body at a state (torques about its centre of
  // mass). `pushing` fixes which points push; null lets the law decide at
  // this state. The points' forces times `weight` are added to `impulses`
  // when it is given.
  std::vector<NetWrench> contactWrenches(const States& states, const Rotations& rotations,
                                      const std::vector<char>* pushing, double weight,
                                      PointImpulses* impulses) const;
  std::vector<StateRate> rates(const States& states, const Rotations& rotations,
                               const std::vector<char>* pushing, double weight,
                               PointImpulses* impulses) const;
  States rk4(const States& start, const Rotations& rotations, const std::vector<char>* pushing,
             double h, PointImpulses* impulses) const;
  States rk4WithSwitches(double h);

  std::vector<SystemBody> m_bodies;
  std::vector<int> m_systemIndex;         // by dense index: index into m_bodies, or -1
  std::vector<BodyMotion> m_fixedMotion;  // by dense index: static bodies (others unused)
  std::vector<PenaltyPoint> m_points;
  PenaltyLaw m_law;
  PointImpulses m_impulses;
};

Mat3 rotationOf(const RigidState& state) {
  return state.orientation.normalized().toRotationMatrix();
}

std::vector<BodyMotion> PenaltySystem::motions(const States& states,
                                               const Rotations& rotations) const {
  std::vector<BodyMotion> out(states.size());
  for (std::size_t j = 0; j < states.size(); ++j) {
    const BodyDynamics& dynamics = m_bodies[j].dynamics;
    out[j].position = states[j].position;
    out[j].rotation = rotations[j];
    out[j].linearVelocity = states[j].linearMomentum * dynamics.inverseMass;
    out[j].angularVelocity =
        angularVelocityFrom(rotations[j], dynamics.inverseInertiaBody, states[j].angularMomentum);
  }
  return out;
}

PenaltySystem::Switches PenaltySystem::switchesAt(const States& states,
                                                  const Rotations& rotations) const {
  const std::vector<BodyMotion> moving = motions(states, rotations);
  Switches switches;
  switches.pushing.assign(m_points.size(), 0);
  switches.springForce.assign(m_points.size(), 0.0);
  switches.linearForce.assign(m_points.size(), 0.0);
  for (std::size_t p = 0; p < m_points.size(); ++p) {
    const PenaltyPoint& point = m_points[p];
    const PenaltyGap gap =
        penaltyGap(point, motionOf(point.bodyA, moving), motionOf(point.bodyB, moving));
    switches.pushing[p] = penaltyPushes(m_law, point, gap) ? 1 : 0;
    switches.springForce[p] = point.stiffness * gap.depth;
    switches.linearForce[p] = linearPenaltyForce(point, gap);
  }
  return switches;
}

std::vector<NetWrench> PenaltySystem::contactWrenches(const States& states, const Rotations& rotations,
                                                   const std::vector<char>* pushing, double weight,
                                                   PointImpulses* impulses) const {
  const std::vector<BodyMotion> moving = motions(states, rotations);
  std::vector<NetWrench> wrenches(states.size());
  for (std::size_t p = 0; p < m_points.size(); ++p) {
    const PenaltyPoint& point = m_points[p];
    const BodyMotion& a = motionOf(point.bodyA, moving);
    const BodyMotion& b = motionOf(point.bodyB, moving);
    const PenaltyGap gap = penaltyGap(point, a, b);
    const bool pushes = pushing != nullptr ? (*pushing)[p] != 0 : penaltyPushes(m_law, point, gap);
    if (!pushes) continue;
    const PenaltyForce force = penaltyForce(point, gap, true);
    if (const int j = m_systemIndex[static_cast<std::size_t>(point.bodyA)]; j >= 0) {
      wrenches[static_cast<std::size_t>(j)].force -= force.onB;
      wrenches[static_cast<std::size_t>(j)].torque -= (force.point - a.position).cross(force.onB);
    }
    if (const int j = m_systemIndex[static_cast<std::size_t>(point.bodyB)]; j >= 0) {
      wrenches[static_cast<std::size_t>(j)].force += force.onB;
      wrenches[static_cast<std::size_t>(j)].torque += (force.point - b.position).cross(force.onB);
    }
    if (impulses != nullptr) {
      impulses->normal[p] += weight * force.normal;
      impulses->tangent[p] += weight * force.friction;
    }
  }
  return wrenches;
}

std::vector<StateRate> PenaltySystem::rates(const States& states, const Rotations& rotations,
                                            const std::vector<char>* pushing, double weight,
                                            PointImpulses* impulses) const {
  const std::vector<NetWrench> contact = contactWrenches(states, rotations, pushing, weight, impulses);
  std::vector<StateRate> out(states.size());
  for (std::size_t j = 0; j < states.size(); ++j) {
    out[j] = stateRate(states[j], rotations[j], m_bodies[j].dynamics, m_bodies[j].inputs);
    out[j].force += contact[j].force;
    out[j].torque += contact[j].torque;
  }
  return out;
}

PenaltySystem::States PenaltySystem::rk4(const States& start, const Rotations& rotations,
                                         const std::vector<char>* pushing, double h,
                                         PointImpulses* impulses) const {
  // The classical stages over the stacked state of all the system's bodies;
  // a point's impulse is its force under the same weights (h/6, h/3, h/3,
  // h/6), i.e. the momentum it actually gave.
  const std::size_t n = start.size();
  const auto stage = [&](const std::vector<StateRate>& k, double fraction, States& states,
                         Rotations& stageRotations) {
    for (std::size_t j = 0; j < n; ++j) {
      states[j] = advanceState(start[j], k[j], fraction * h);
      stageRotations[j] = rotationOf(states[j]);
    }
  };
  States states(n);
  Rotations stageRotations(n);
  const std::vector<StateRate> k1 = rates(start, rotations, pushing, h / 6.0, impulses);
  stage(k1, 0.5, states, stageRotations);
  const std::vector<StateRate> k2 = rates(states, stageRotations, pushing, h / 3.0, impulses);
  stage(k2, 0.5, states, stageRotations);
  const std::vector<StateRate> k3 = rates(states, stageRotations, pushing, h / 3.0, impulses);
  stage(k3, 1.0, states, stageRotations);
  const std::vector<StateRate> k4 = rates(states, stageRotations, pushing, h / 6.0, impulses);
  States end(n);
  for (std::size_t j = 0; j < n; ++j) end[j] = rk4Combine(start[j], k1[j], k2[j], k3[j], k4[j], h);
  return end;
}

PenaltySystem::States PenaltySystem::rk4WithSwitches(double h) {
  // The normal force jumps where a point starts or stops pushing (by c ḋ at
  // touch-down), and a Runge–Kutta step across a jump of the right-hand side
  // is only first-order accurate. So the step is cut at the switches: each
  // piece is integrated with the set of pushing points held (a smooth
  // right-hand side), and a piece that ends with another set is shortened to
  // the moment the set changes, bracketed to 1e-12 dt, after which the rest
  // of the step is taken with the new set. The moment is found by regula
  // falsi (Illinois variant) on the switching values (about six RK4 trials a
  // switch). Past kMaxSwitches in one step the law decides at every stage
  // (a safety net for chattering contacts).
  constexpr int kMaxSwitches = 8;
  constexpr int kMaxIterations = 100;
  const double tolerance = 1e-12 * h;
  States states(m_bodies.size());
  Rotations rotations(m_bodies.size());
  for (std::size_t j = 0; j < m_bodies.size(); ++j) {
    states[j] = m_bodies[j].start;
    rotations[j] = m_bodies[j].startRotation;
  }
  const auto rotationsOf = [](const States& of) {
    Rotations out(of.size());
    for (std::size_t j = 0; j < of.size(); ++j) out[j] = rotationOf(of[j]);
    return out;
  };
  double remaining = h;
  for (int switches = 0;; ++switches) {
    if (switches == kMaxSwitches) return rk4(states, rotations, nullptr, remaining, &m_impulses);
    Switches atLow = switchesAt(states, rotations);
    const std::vector<char> pushing = atLow.pushing;
    // Which value's root is each point's switch, smooth over the piece: a
    // clamped point stops pushing where k d + c ḋ reaches zero (before d
    // does, as ḋ < 0 there), and starts, if it is still in the ground, where
    // k d + c ḋ turns positive; otherwise the switch is d = 0 (at touch-down
    // c ḋ > 0).
    std::vector<char> byForce(m_points.size(), 0);
    for (std::size_t p = 0; p < m_points.size(); ++p)
      byForce[p] = m_law == PenaltyLaw::Clamped && (pushing[p] != 0 || atLow.springForce[p] > 0.0);
    // The switches at the end of a piece of length t with `pushing` held.
    const auto after = [&](double t) {
      const States end = rk4(states, rotations, &pushing, t, nullptr);
      return switchesAt(end, rotationsOf(end));
    };
    // Most steps have no switch: the whole rest of the step, kept if so.
    PointImpulses pieceImpulses{std::vector<double>(m_points.size(), 0.0),
                                std::vector<Vec3>(m_points.size(), Vec3::Zero())};
    States whole = rk4(states, rotations, &pushing, remaining, &pieceImpulses);
    Switches atHigh = switchesAt(whole, rotationsOf(whole));
    if (atHigh.pushing == pushing) {
      for (std::size_t p = 0; p < m_points.size(); ++p) {
        m_impulses.normal[p] += pieceImpulses.normal[p];
        m_impulses.tangent[p] += pieceImpulses.tangent[p];
      }
      return whole;
    }
    double low = 0.0, high = remaining;
    // Illinois: the value of an end kept twice in a row is halved, so that
    // regula falsi does not creep up on the root from one side.
    double scaleLow = 1.0, scaleHigh = 1.0;
    int keptLow = 0, keptHigh = 0;
    for (int i = 0; i < kMaxIterations && high - low > tolerance; ++i) {
      const double width = high - low, oldLow = low, oldHigh = high;
      // The earliest crossing, linearly between the bracket's ends, among
      // the points that have switched by `high`.
      double guess = std::numeric_limits<double>::infinity();
      for (std::size_t p = 0; p < pushing.size(); ++p) {
        if (atHigh.pushing[p] == pushing[p]) continue;
        const double a = scaleLow * (byForce[p] ? atLow.linearForce[p] : atLow.springForce[p]);
        const double b = scaleHigh * (byForce[p] ? atHigh.linearForce[p] : atHigh.springForce[p]);
        const double t = low + width * a / (a - b);
        if (t >= low && t <= high) guess = std::min(guess, t);
      }
      if (!(guess <= high)) guess = low + 0.5 * width;
      // Never at an end: an end at the root (to rounding) is then bracketed
      // by the next evaluation.
      guess = std::clamp(guess, low + 0.5 * tolerance, high - 0.5 * tolerance);
      Switches at = after(guess);
      if (at.pushing == pushing) {
        low = guess;
        atLow = std::move(at);
      } else {
        high = guess;
        atHigh = std::move(at);
      }
      keptLow = low == oldLow ? keptLow + 1 : 0;
      keptHigh = high == oldHigh ? keptHigh + 1 : 0;
      scaleLow = keptLow >= 2 ? 0.5 * scaleLow : (keptLow == 0 ? 1.0 : scaleLow);
      scaleHigh = keptHigh >= 2 ? 0.5 * scaleHigh : (keptHigh == 0 ? 1.0 : scaleHigh);
    }
    // To just past the switch (the set has changed at `high`).
    states = rk4(states, rotations, &pushing, high, &m_impulses);
    rotations = rotationsOf(states);
    remaining -= high;
    if (!(remaining > 0.0)) return states;
  }
}

std::vector<RigidState> PenaltySystem::step(IntegratorKind kind, double h) {
  const std::size_t n = m_bodies.size();
  States start(n);
  Rotations rotations(n);
  for (std::size_t j = 0; j < n; ++j) {
    start[j] = m_bodies[j].start;
    rotations[j] = m_bodies[j].startRotation;
  }
  switch (kind) {
    case IntegratorKind::Rk4:
      return rk4WithSwitches(h);
    case IntegratorKind::ExplicitEuler: {
      // Every right-hand side at the step start, contact forces included.
      const std::vector<StateRate> k = rates(start, rotations, nullptr, h, &m_impulses);
      States end(n);
      for (std::size_t j = 0; j < n; ++j) {
        end[j] = advanceState(start[j], k[j], h);
        end[j].orientation = end[j].orientation.normalized();
      }
      return end;
    }
    case IntegratorKind::SemiImplicitEuler: {
      // The contact forces of the step start, held over the step, are a kick
      // of the momenta by h F before the body's own semi-implicit step: the
      // same P' = (P + h (F_body + F_contact)) / (1 + c h), then x and q with
      // the new velocities.
      const std::vector<NetWrench> contact =
          contactWrenches(start, rotations, nullptr, h, &m_impulses);
      States end(n);
      for (std::size_t j = 0; j < n; ++j) {
        RigidState kicked = start[j];
        kicked.linearMomentum += h * contact[j].force;
        kicked.angularMomentum += h * contact[j].torque;
        end[j] = semiImplicitEulerStep(kicked, rotations[j], m_bodies[j].dynamics,
                                       m_bodies[j].inputs, h);
      }
      return end;
    }
  }
  return start;
}

BodyMotion motionAtStart(const Body& body) {
  return {body.position(), body.rotation(), body.linearVelocity(), body.angularVelocity()};
}

}  // namespace

void stepPenalty(WorldData& world) {
  // Spring–damper forces from the penetration (a penalty method, the
  // alternative to impulses that Baraff's rigid-body notes describe):
  // along the normal F = k d + c ḋ (PenaltyLaw: clamped at zero or not),
  // tangentially a viscous force capped at the Coulomb limit μ F_n.
  // Stiffness and damping are per manifold and shared by its points, so a
  // resting body sinks by m g / k whatever its number of contact points. The
  // forces are evaluated wherever the integrator evaluates forces: at the
  // step start for the Euler methods, at every stage for RK4. They are the
  // world's own, never added to the bodies' external loads.
  const double dt = world.settings.dt;
  const ContactConfig& config = world.settings.contact;
  findContacts(world);
  const std::vector<BodyContact>& detected = world.detector->contacts();
  const std::size_t n = world.bodies.size();
  for (Body& body : world.bodies) body.setSleeping(false);  // the penalty model does not sleep bodies

  // The system: every dynamic body that a contact touches.
  std::vector<int> systemIndex(n, -1);
  std::vector<char> inSystem(n, 0);
  std::vector<SystemBody> system;
  std::vector<int> denseOf;
  for (const BodyContact& c : detected) {
    for (const int i : {c.bodyA, c.bodyB}) {
      const std::size_t k = static_cast<std::size_t>(i);
      if (world.bodies[k].isStatic() || inSystem[k]) continue;
      inSystem[k] = 1;
      systemIndex[k] = static_cast<int>(system.size());
      denseOf.push_back(i);
      const Body& body = world.bodies[k];
      const ForceInputs inputs = forcesOn(world, k);
      system.push_back({body.state(), body.rotation(), body.dynamics(), inputs});
    }
  }

  std::vector<BodyMotion> fixedMotion(n);
  std::vector<PenaltyPoint> points;
  std::vector<SolvedManifold> records;
  records.reserve(detected.size());
  for (const BodyContact& c : detected) {
    const Body& a = world.bodies[static_cast<std::size_t>(c.bodyA)];
    const Body& b = world.bodies[static_cast<std::size_t>(c.bodyB)];
    const BodyMotion motionA = motionAtStart(a), motionB = motionAtStart(b);
    fixedMotion[static_cast<std::size_t>(c.bodyA)] = motionA;
    fixedMotion[static_cast<std::size_t>(c.bodyB)] = motionB;
    const PairMaterial material =
        combineMaterials(a.description().material, b.description().material);
    const ContactManifold& m = c.manifold;
    const double share = 1.0 / std::max(1, m.pointCount);
    SolvedManifold record = manifoldIdentity(c, a.serial(), b.serial());
    for (int p = 0; p < m.pointCount; ++p) {
      const ContactPoint& detectedPoint = m.points[static_cast<std::size_t>(p)];
      PenaltyPoint point =
          makePenaltyPoint(c.bodyA, c.bodyB, motionA, motionB, detectedPoint.pointA,
                           detectedPoint.pointB, detectedPoint.depth, m.normal);
      point.stiffness = share * config.penaltyStiffness;
      point.damping = share * config.penaltyDamping;
      point.frictionDamping = share * config.penaltyFrictionDamping;
      point.friction = material.friction;
      const PenaltyGap gap = penaltyGap(point, motionA, motionB);
      SolvedContactPoint& out = record.points[p];
      out.point = 0.5 * (detectedPoint.pointA + detectedPoint.pointB);
      out.depth = detectedPoint.depth;
      out.relativeNormalVelocity = gap.normalVelocity;
      out.featureId = detectedPoint.featureId;
      const Vec3 tangential = gap.relativeVelocity - gap.normalVelocity * m.normal;
      out.sticking = tangential.norm() < config.solver.stickVelocity;
      points.push_back(point);
    }
    records.push_back(record);
  }

  integrateFree(world, dt, inSystem);
  if (!system.empty()) {
    PenaltySystem penalty(std::move(system), std::move(systemIndex), std::move(fixedMotion), points,
                          config.penaltyLaw);
    const std::vector<RigidState> next = penalty.step(world.settings.integrator, dt);
    for (std::size_t j = 0; j < next.size(); ++j) {
      Body& body = world.bodies[static_cast<std::size_t>(denseOf[j])];
      body.moveTo(next[j]);
    }
    std::size_t index = 0;
    for (SolvedManifold& record : records) {
      for (int p = 0; p < record.pointCount; ++p, ++index) {
        record.points[p].normalImpulse = penalty.impulses().normal[index];
        record.points[p].tangentImpulse = penalty.impulses().tangent[index];
      }
    }
  }
  world.contacts = std::move(records);
}

}  // namespace rbsim
