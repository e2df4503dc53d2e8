// The joint step of the jointed bodies (joint/joint_solver.h): RATTLE for
// islands that touch nothing, the contact path's semi-implicit step around
// the same projection for islands in contact; and which bodies the joints
// take out of the other paths (the pairs they join never reach the narrow
// phase: collision_filtering.cpp).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "physics/body/body.h"
#include "physics/body/external_load.h"
#include "physics/body/integrator.h"
#include "physics/collision/body_contact.h"
#include "physics/common/step_part.h"
#include "physics/joint/joint_constraint.h"
#include "physics/joint/joint_solver.h"
#include "physics/joint/joint_velocity_projection.h"
#include "physics/math/rotation_matrix.h"
#include "physics/solver/contact_solver.h"
#include "physics/world/step_stages.h"
#include "physics/world/world_data.h"

namespace rbsim {

namespace {

// The direct effort and a drive's gravity compensation as the actuator
// gives them: capped at its effort limit.
double appliedEffort(const JointConstraint& joint) {
  const JointDef& def = joint.def;
  return std::clamp(def.effort + joint.gravityFeedForward, -def.actuatorLimits.effort, def.actuatorLimits.effort);
}

// A joint's sides as the joint solver takes them: by `local` index, or a
// fixed pose (-1: the world, a static body, a body outside the step);
// whether one of them moves.
bool placeSides(const WorldData& world, const JointConstraint& joint, const std::vector<int>& local, int& indexA,
                int& indexB, JointSidePose& fixedA, JointSidePose& fixedB) {
  bool anyMoving = false;
  for (const bool sideB : {false, true}) {
    const BodyId id = sideB ? joint.def.bodyB : joint.def.bodyA;
    int& index = sideB ? indexB : indexA;
    JointSidePose& fixed = sideB ? fixedB : fixedA;
    index = -1;
    if (id.isNull()) continue;
    const std::size_t i = denseIndexOf(world, id);
    index = local[i];
    if (index < 0) fixed = jointSidePose(world.bodies[i]);  // static
    anyMoving = anyMoving || index >= 0;
  }
  return anyMoving;
}

// A joint's coordinate at its bodies' poses now.
double coordinateNow(const WorldData& world, const JointConstraint& joint) {
  JointSidePose poses[2];
  const BodyId ids[2] = {joint.def.bodyA, joint.def.bodyB};
  for (int side = 0; side < 2; ++side)
    if (!ids[side].isNull()) poses[side] = jointSidePose(world.bodies[denseIndexOf(world, ids[side])]);
  return joint.coordinate(poses[0], poses[1]);
}

// The enforced joints with a moving side as the joint solver takes them,
// with the joint's index; then the mimic couplings of followers whose
// leader is enforced too (linkJoint: the follower's index).
void collectJointLinks(const WorldData& world, const std::vector<int>& local, std::vector<JointLink>& links,
                       std::vector<std::size_t>& linkJoint) {
  links.clear();
  linkJoint.clear();
  for (std::size_t j = 0; j < world.joints.size(); ++j) {
    const JointConstraint& joint = world.joints[j];
    if (!jointIsEnforced(world, joint)) continue;
    JointLink link;
    link.joint = &joint;
    if (!placeSides(world, joint, local, link.bodyA, link.bodyB, link.fixedA, link.fixedB)) continue;
    links.push_back(link);
    linkJoint.push_back(j);
  }
  for (std::size_t j = 0; j < world.joints.size(); ++j) {
    const JointConstraint& follower = world.joints[j];
    if (!follower.def.mimic.enabled || !jointIsEnforced(world, follower)) continue;
    const int leaderIndex = enforcedLeaderOf(world, follower);
    if (leaderIndex < 0) continue;
    const JointConstraint& leader = world.joints[static_cast<std::size_t>(leaderIndex)];
    JointLink link;
    link.joint = &follower;
    link.leader = &leader;
    const bool followerMoves = placeSides(world, follower, local, link.bodyA, link.bodyB, link.fixedA, link.fixedB);
    const bool leaderMoves = placeSides(world, leader, local, link.bodyC, link.bodyD, link.fixedC, link.fixedD);
    if (!followerMoves && !leaderMoves) continue;
    link.followerFrom = coordinateNow(world, follower);
    link.leaderFrom = coordinateNow(world, leader);
    link.errorFrom = follower.mimicError;
    links.push_back(link);
    linkJoint.push_back(j);
  }
}

// An impulse `lambda` along a joint's axis row at the start or current
// poses of `bodies`: on B, and its reaction on A.
void pushAlongAxis(const JointLink& link, std::vector<JointBody>& bodies, bool atStart, double lambda) {
  JointRow row;
  link.joint->axisRow(sidePose(link, bodies, false, atStart), sidePose(link, bodies, true, atStart), row);
  if (link.bodyA >= 0) {
    JointBody& body = bodies[static_cast<std::size_t>(link.bodyA)];
    body.linearMomentum += lambda * row.linearA;
    body.angularMomentum += lambda * row.angularA;
  }
  if (link.bodyB >= 0) {
    JointBody& body = bodies[static_cast<std::size_t>(link.bodyB)];
    body.linearMomentum += lambda * row.linearB;
    body.angularMomentum += lambda * row.angularB;
  }
}

}  // namespace

const std::vector<char>& findActuatedBodies(WorldData& world) {
  const StepPartScope inJoints(StepPart::Joints);
  // A drive moves its joint until it settles; a body's own sleep thresholds
  // (cm/s) are too coarse for a servo creeping to its target, so a drive's
  // joint counts as moving down to this rate.
  constexpr double kDriveSettledRate = 1e-4;  // rad/s or m/s
  std::vector<char>& busy = world.jointScratch.actuated;
  busy.clear();
  for (std::size_t j = 0; j < world.joints.size(); ++j) {
    const JointDef& def = world.joints[j].def;
    const bool motorMoves = def.motor.enabled && def.motor.targetRate != 0.0;
    if (!motorMoves && !def.drive.enabled) continue;
    if (!jointIsEnforced(world, world.joints[j])) continue;
    if (!motorMoves && std::abs(jointStateAt(world, static_cast<int>(j)).rate) <= kDriveSettledRate) continue;
    if (busy.empty()) busy.assign(world.bodies.size(), 0);
    for (const BodyId body : {def.bodyA, def.bodyB})
      if (!body.isNull()) busy[denseIndexOf(world, body)] = 1;
  }
  return busy;
}

const std::vector<char>& findJointedBodies(WorldData& world) {
  const StepPartScope inJoints(StepPart::Joints);
  std::vector<char>& jointed = world.jointScratch.jointed;
  jointed.clear();
  for (const JointConstraint& joint : world.joints) {
    if (!jointIsEnforced(world, joint)) continue;
    for (const BodyId id : {joint.def.bodyA, joint.def.bodyB}) {
      if (id.isNull()) continue;
      const std::size_t i = denseIndexOf(world, id);
      const Body& body = world.bodies[i];
      if (body.isStatic() || body.isSleeping()) continue;
      if (jointed.empty()) jointed.assign(world.bodies.size(), 0);
      jointed[i] = 1;
    }
  }
  return jointed;
}


const VelocityProjection* addJointedIslandsInContact(WorldData& world, ContactStep& step,
                                                     const std::vector<char>& jointed,
                                                     const std::vector<int>& islandOf) {
  const StepPartScope inJoints(StepPart::Joints);
  JointStepScratch& scratch = world.jointScratch;
  const std::size_t n = world.bodies.size();
  std::vector<char>& touching = scratch.touching;  // per island root
  touching.assign(n, 0);
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!jointed[i] || !step.solving[i]) continue;
    touching[static_cast<std::size_t>(islandOf[i])] = 1;
    any = true;
  }
  if (!any) return nullptr;
  std::vector<int>& local = scratch.local;
  local.assign(n, -1);
  std::vector<std::size_t>& solverIndex = scratch.dense;
  solverIndex.clear();
  std::vector<JointBody>& bodies = scratch.bodies;
  bodies.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (!jointed[i] || !touching[static_cast<std::size_t>(islandOf[i])]) continue;
    step.solving[i] = 1;
    const Body& body = world.bodies[i];
    local[i] = static_cast<int>(bodies.size());
    solverIndex.push_back(i);
    JointBody jb;
    jb.startPosition = body.position();
    jb.startOrientation = body.orientation();
    jb.startInverseInertia = body.inverseInertiaWorld();
    jb.inverseMass = body.inverseMass();
    bodies.push_back(jb);
  }
  std::vector<JointLink>& links = scratch.links;
  std::vector<std::size_t>& linkJoint = scratch.linkJoint;
  collectJointLinks(world, local, links, linkJoint);
  // Joints of islands that touch nothing have no side here: leave them out.
  std::vector<JointLink>& inContact = scratch.inContact;
  inContact.clear();
  for (const JointLink& link : links)
    if (link.bodyA >= 0 || link.bodyB >= 0 || link.bodyC >= 0 || link.bodyD >= 0) inContact.push_back(link);
  // Their K₀ was made at the end of the last step (its velocity
  // projection), where this one starts: the joint solver keeps it.
  scratch.projection.make(inContact, bodies, solverIndex, world.jointSolver.get());
  return &scratch.projection;
}

void actuateJointedIslandsInContact(WorldData& world, const ContactStep& step, const std::vector<char>& jointed,
                                    double h) {
  const StepPartScope inJoints(StepPart::Joints);
  world.contactActuation.clear();
  JointStepScratch& scratch = world.jointScratch;
  const std::size_t n = world.bodies.size();
  std::vector<int>& local = scratch.local;
  local.assign(n, -1);
  std::vector<std::size_t>& dense = scratch.dense;
  dense.clear();
  std::vector<JointBody>& bodies = scratch.bodies;
  bodies.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (jointed.empty() || !jointed[i] || !step.solving[i]) continue;
    const Body& body = world.bodies[i];
    const SolverBody& sb = world.solverBodies[i];
    local[i] = static_cast<int>(dense.size());
    dense.push_back(i);
    JointBody jb;
    jb.startPosition = body.position();
    jb.startOrientation = body.orientation();
    jb.position = jb.startPosition;
    jb.orientation = jb.startOrientation;
    jb.startInverseInertia = body.inverseInertiaWorld();
    jb.inverseMass = body.inverseMass();
    jb.linearMomentum = body.mass() * sb.linearVelocity;
    jb.angularMomentum = body.inertiaWorld() * sb.angularVelocity;
    bodies.push_back(jb);
  }
  if (dense.empty()) return;
  std::vector<JointLink>& links = scratch.links;
  std::vector<std::size_t>& linkJoint = scratch.linkJoint;
  collectJointLinks(world, local, links, linkJoint);
  if (links.empty()) return;
  for (JointLink& link : links) link.wholeKick = true;
  // The direct efforts, as impulses along each joint's axis row over h.
  for (const JointLink& link : links) {
    const double effort = appliedEffort(*link.joint);
    if (effort == 0.0 || link.isCoupling() || !link.joint->hasAxis()) continue;
    pushAlongAxis(link, bodies, true, effort * h);
  }
  std::vector<JointLinkResult>& results = scratch.results;
  world.jointSolver->actuateBeforeContacts(links, bodies, h, results);
  for (std::size_t k = 0; k < dense.size(); ++k) {
    SolverBody& sb = world.solverBodies[dense[k]];
    sb.linearVelocity = bodies[k].inverseMass * bodies[k].linearMomentum;
    sb.angularVelocity = sb.inverseInertia * bodies[k].angularMomentum;
  }
  world.contactActuation.assign(world.joints.size(), JointLinkResult{});
  for (std::size_t l = 0; l < links.size(); ++l) world.contactActuation[linkJoint[l]] = results[l];
}

void stepJointedBodies(WorldData& world, const std::vector<char>& jointed, const std::vector<char>& solving,
                       const std::vector<int>& islandOf, double h) {
  const StepPartScope inJoints(StepPart::Joints);
  if (jointed.empty()) return;
  JointStepScratch& scratch = world.jointScratch;
  const std::size_t n = world.bodies.size();
  // Islands with a jointed body in contact take the semi-implicit step.
  std::vector<char>& contactIsland = scratch.contactIsland;
  contactIsland.clear();
  if (!solving.empty()) {
    contactIsland.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      if (jointed[i] && solving[i]) contactIsland[static_cast<std::size_t>(islandOf[i])] = 1;
  }
  // The jointed bodies: where they start, their momenta after the first
  // half kick (and the contact impulses, for those the contact solver
  // moved), the contact impulses alone, the split-impulse pseudo-velocities.
  std::vector<int>& local = scratch.local;
  local.assign(n, -1);
  std::vector<std::size_t>& dense = scratch.dense;
  std::vector<Momenta>& kicked = scratch.kicked;
  std::vector<Momenta>& contactImpulse = scratch.contactImpulse;
  std::vector<Vec3>& pseudoLinear = scratch.pseudoLinear;
  std::vector<Vec3>& pseudoAngular = scratch.pseudoAngular;
  std::vector<char>& staggered = scratch.staggered;  // per jointed body: RATTLE's half kicks (else the whole kick first)
  dense.clear();
  kicked.clear();
  contactImpulse.clear();
  pseudoLinear.clear();
  pseudoAngular.clear();
  staggered.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (!jointed[i]) continue;
    const Body& body = world.bodies[i];
    local[i] = static_cast<int>(dense.size());
    dense.push_back(i);
    const bool halves = contactIsland.empty() || !contactIsland[static_cast<std::size_t>(islandOf[i])];
    staggered.push_back(halves ? 1 : 0);
    const Momenta free = halves ? firstHalfKick(body.state(), body.rotation(), body.dynamics(), forcesOn(world, i), h)
                                : integrateMomenta(body.state(), body.rotation(), body.dynamics(), forcesOn(world, i), h);
    Momenta withContacts = free;
    Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
    if (!solving.empty() && solving[i]) {
      const SolverBody& sb = world.solverBodies[i];
      withContacts = {body.mass() * sb.linearVelocity, body.inertiaWorld() * sb.angularVelocity};
      linear = sb.pseudoLinear;
      angular = sb.pseudoAngular;
    }
    kicked.push_back(withContacts);
    contactImpulse.push_back({withContacts.linear - free.linear, withContacts.angular - free.angular});
    pseudoLinear.push_back(linear);
    pseudoAngular.push_back(angular);
  }
  std::vector<JointLink>& links = scratch.links;
  std::vector<std::size_t>& linkJoint = scratch.linkJoint;
  collectJointLinks(world, local, links, linkJoint);
  // An island in contact had its axes' laws and direct efforts before the
  // contact solve (actuateJointedIslandsInContact): they are in `kicked`.
  const bool actuatedBefore = !world.contactActuation.empty();
  for (JointLink& link : links) {
    const int any = link.bodyA >= 0 ? link.bodyA : link.bodyB >= 0 ? link.bodyB : link.bodyC >= 0 ? link.bodyC : link.bodyD;
    link.wholeKick = actuatedBefore && any >= 0 && staggered[static_cast<std::size_t>(any)] == 0;
    link.inContact = any >= 0 && staggered[static_cast<std::size_t>(any)] == 0;
  }

  // The step in `parts` equal sub-steps, each a whole RATTLE step (half
  // kick, drift and projection, half kick, velocity projection); the
  // contact impulses and the pseudo-velocities' displacement go into the
  // first. Returns whether every projection converged.
  JointSolver& solver = *world.jointSolver;
  std::vector<RigidState>& ends = scratch.ends;
  ends.resize(dense.size());
  std::vector<Vec3>& reactionLinear = scratch.reactionLinear;
  std::vector<Vec3>& reactionAngular = scratch.reactionAngular;
  reactionLinear.resize(links.size());
  reactionAngular.resize(links.size());
  // The direct efforts, as impulses along each joint's axis row over
  // `duration` at the current poses of `bodies` (start or end).
  const auto applyEfforts = [&](std::vector<JointBody>& bodies, bool atStart, double duration, bool staggeredPart) {
    for (const JointLink& link : links) {
      const double effort = appliedEffort(*link.joint);
      if (effort == 0.0 || link.isCoupling() || !link.joint->hasAxis()) continue;
      const int any = link.bodyA >= 0 ? link.bodyA : link.bodyB;
      if ((staggered[static_cast<std::size_t>(any)] != 0) != staggeredPart) continue;
      pushAlongAxis(link, bodies, atStart, effort * duration);
    }
  };
  std::vector<double>& axisImpulse = scratch.axisImpulse;
  std::vector<int>& atLimit = scratch.atLimit;
  std::vector<double>& couplingError = scratch.couplingError;
  axisImpulse.assign(links.size(), 0.0);
  atLimit.assign(links.size(), 0);
  couplingError.assign(links.size(), 0.0);
  const auto attempt = [&](int parts) {
    const double s = h / parts;
    std::fill(axisImpulse.begin(), axisImpulse.end(), 0.0);
    bool converged = true;
    std::fill(reactionLinear.begin(), reactionLinear.end(), Vec3::Zero());
    std::fill(reactionAngular.begin(), reactionAngular.end(), Vec3::Zero());
    for (std::size_t k = 0; k < dense.size(); ++k) ends[k] = world.bodies[dense[k]].state();
    for (int part = 0; part < parts; ++part) {
      std::vector<JointBody>& bodies = scratch.bodies;
      bodies.assign(dense.size(), JointBody{});
      for (std::size_t k = 0; k < dense.size(); ++k) {
        const Body& body = world.bodies[dense[k]];
        const RigidState& start = ends[k];
        const Mat3 rotation = start.orientation.toRotationMatrix();
        JointBody& jb = bodies[k];
        jb.startPosition = start.position;
        jb.startOrientation = start.orientation;
        jb.startInverseInertia = rotatedDiagonal(rotation, body.dynamics().inverseInertiaBody);
        jb.inverseMass = body.inverseMass();
        Momenta momenta = kicked[k];
        if (parts > 1) {
          momenta = staggered[k] ? firstHalfKick(start, rotation, body.dynamics(), forcesOn(world, dense[k]), s)
                                 : integrateMomenta(start, rotation, body.dynamics(), forcesOn(world, dense[k]), s);
          if (part == 0) {
            momenta.linear += contactImpulse[k].linear;
            momenta.angular += contactImpulse[k].angular;
          }
        }
        jb.linearMomentum = momenta.linear;
        jb.angularMomentum = momenta.angular;
        jb.startLinearMomentum = start.linearMomentum;
        jb.startAngularMomentum = start.angularMomentum;
        if (part == 0) {
          jb.pseudoLinear = static_cast<double>(parts) * pseudoLinear[k];
          jb.pseudoAngular = static_cast<double>(parts) * pseudoAngular[k];
        }
      }
      applyEfforts(bodies, true, 0.5 * s, true);  // RATTLE's first half kick (an island in contact had its whole kick)
      std::vector<JointLinkResult>& results = scratch.results;
      converged = solver.solvePositions(links, bodies, s, JointSolverSettings{}, results) && converged;
      // The second half kick at the end poses, then the velocities tangent
      // to the joints there. A body's own damping is implicit over all that
      // the half adds, forces, efforts, the joints' and their axes' impulses:
      // P = (P½ + the half's impulses) / (1 + c s/2). The projection then
      // sees the body's inverse mass and inertia shrunk by that factor (its
      // velocity per impulse), and the momenta shrink after it; damping the
      // forces alone and projecting after it was first order, each step's
      // constraint impulse O(s) missing its share of c s/2.
      std::vector<Mat3>& endInverseInertia = scratch.endInverseInertia;
      endInverseInertia.resize(bodies.size());
      std::vector<JointStepScratch::Shrink>& shrink = scratch.shrink;  // 1 / (1 + c s/2) of P and L, and 1/m
      shrink.assign(bodies.size(), JointStepScratch::Shrink{});
      bool damped = false;
      for (std::size_t k = 0; k < bodies.size(); ++k) {
        const Body& body = world.bodies[dense[k]];
        JointBody& jb = bodies[k];
        const RigidState state{jb.position, jb.orientation, jb.linearMomentum, jb.angularMomentum};
        const Mat3 rotation = state.orientation.toRotationMatrix();
        endInverseInertia[k] = rotatedDiagonal(rotation, body.dynamics().inverseInertiaBody);
        if (!staggered[k]) continue;
        BodyDynamics undamped = body.dynamics();
        undamped.linearDamping = undamped.angularDamping = 0.0;
        const Momenta end = integrateMomenta(state, rotation, undamped, forcesOn(world, dense[k]), 0.5 * s);
        jb.linearMomentum = end.linear;
        jb.angularMomentum = end.angular;
        const BodyDynamics& dynamics = body.dynamics();
        if (dynamics.linearDamping == 0.0 && dynamics.angularDamping == 0.0) continue;
        damped = true;
        shrink[k] = {1.0 / (1.0 + 0.5 * s * dynamics.linearDamping), 1.0 / (1.0 + 0.5 * s * dynamics.angularDamping),
                     jb.inverseMass};
        jb.inverseMass *= shrink[k].linear;
        endInverseInertia[k] *= shrink[k].angular;
      }
      applyEfforts(bodies, false, 0.5 * s, true);  // the second half kick
      solver.projectVelocities(links, bodies, endInverseInertia, s, results);
      if (damped) {
        for (std::size_t k = 0; k < bodies.size(); ++k) {
          if (shrink[k].linear == 1.0 && shrink[k].angular == 1.0) continue;
          bodies[k].linearMomentum *= shrink[k].linear;
          bodies[k].angularMomentum *= shrink[k].angular;
          bodies[k].inverseMass = shrink[k].inverseMass;
        }
      }
      for (std::size_t k = 0; k < bodies.size(); ++k)
        ends[k] = {bodies[k].position, bodies[k].orientation, bodies[k].linearMomentum, bodies[k].angularMomentum};
      for (std::size_t l = 0; l < links.size(); ++l) {
        reactionLinear[l] += results[l].linearImpulse;
        reactionAngular[l] += results[l].angularImpulse;
        axisImpulse[l] += results[l].axisImpulse;
        atLimit[l] = results[l].atLimit;
        couplingError[l] = results[l].couplingError;
      }
    }
    return converged;
  };
  // Sub-steps only where one step is too long for the projection to find
  // the joints' closure (fast turns of light links: the start's rows no
  // longer reach it): halve until it converges, up to 16 parts.
  constexpr int kMaxParts = 16;
  for (int parts = 1; !attempt(parts) && parts < kMaxParts;) parts *= 2;

  for (std::size_t k = 0; k < dense.size(); ++k) {
    Body& body = world.bodies[dense[k]];
    body.moveTo(ends[k]);
    noteSpeeds(world, body.linearVelocity().squaredNorm(), body.angularVelocity().squaredNorm());
  }
  if (actuatedBefore) {
    for (std::size_t l = 0; l < links.size(); ++l) {
      if (!links[l].wholeKick) continue;
      const JointLinkResult& before = world.contactActuation[linkJoint[l]];
      reactionLinear[l] += before.linearImpulse;
      reactionAngular[l] += before.angularImpulse;
      axisImpulse[l] += before.axisImpulse;
    }
    world.contactActuation.clear();
  }
  for (std::size_t l = 0; l < links.size(); ++l) {
    JointConstraint& joint = world.joints[linkJoint[l]];
    if (links[l].isCoupling()) continue;
    joint.lastForce = reactionLinear[l] / h;
    joint.lastTorque = reactionAngular[l] / h;
    joint.lastAxisEffort = axisImpulse[l] / h + appliedEffort(joint);
    joint.lastAtLimit = atLimit[l];
  }
  // A coupling's push along its follower's axis is the follower's effort
  // (what drives it: the mimic's transmission); its error carries on.
  for (std::size_t l = 0; l < links.size(); ++l) {
    if (!links[l].isCoupling()) continue;
    JointConstraint& follower = world.joints[linkJoint[l]];
    follower.lastAxisEffort += axisImpulse[l] / h;
    follower.mimicError = couplingError[l];
  }
}

}  // namespace rbsim
