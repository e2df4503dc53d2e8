// Joints in the world: creation and removal, what a joint reports, and the
// joint step of the jointed bodies (joint/joint_solver.h).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "physics/body/body.h"
#include "physics/body/external_load.h"
#include "physics/body/integrator.h"
#include "physics/collision/body_contact.h"
#include "physics/joint/joint_constraint.h"
#include "physics/joint/joint_solver.h"
#include "physics/joint/joint_velocity_projection.h"
#include "physics/math/rotation_matrix.h"
#include "physics/solver/contact_solver.h"
#include "rbsim/physics/world.h"

namespace rbsim {

namespace {

JointSidePose poseOfBody(const Body& body) {
  return {body.position(), body.orientation(), body.rotation()};
}

// The direct effort as the actuator gives it: capped at its effort limit.
double appliedEffort(const JointDef& def) {
  return std::clamp(def.effort, -def.actuatorLimits.effort, def.actuatorLimits.effort);
}

}  // namespace

Expected<JointId> World::createJoint(const JointDef& def) {
  const std::string where = "joint '" + def.name + "'";
  if (def.name.empty()) return Error{"a joint needs a name"};
  if (!findJoint(def.name).isNull()) return Error{where + ": the name is taken by another joint"};
  if (m_settings.contact.model == ContactModel::Penalty)
    return Error{where + ": joints need the impulse contact model (contact.model: impulse)"};
  JointSidePose poses[2];
  bool moves[2] = {false, false};
  const BodyId ids[2] = {def.bodyA, def.bodyB};
  for (int side = 0; side < 2; ++side) {
    if (ids[side].isNull()) continue;  // the world
    if (const std::string why = invalidIdReason(ids[side]); !why.empty())
      return Error{where + ": body_" + (side == 0 ? "a" : "b") + ": " + why};
    const Body& body = m_bodies[denseIndexOf(ids[side])];
    poses[side] = poseOfBody(body);
    moves[side] = !body.isStatic();
  }
  if (!ids[0].isNull() && ids[0] == ids[1]) return Error{where + ": joins a body to itself"};
  if (!moves[0] && !moves[1]) return Error{where + ": neither side moves (both are the world or static)"};
  Expected<JointConstraint> made = makeJointConstraint(def, poses[0], poses[1]);
  if (!made.ok()) return made.error();

  int32_t slot;
  if (!m_freeJointSlots.empty()) {
    const auto lowest = std::min_element(m_freeJointSlots.begin(), m_freeJointSlots.end());
    slot = *lowest;
    m_freeJointSlots.erase(lowest);
  } else {
    slot = static_cast<int32_t>(m_jointSlots.size());
    m_jointSlots.push_back({});
  }
  m_jointSlots[static_cast<std::size_t>(slot)].denseIndex = static_cast<int32_t>(m_joints.size());
  const JointId id{slot + 1, m_jointSlots[static_cast<std::size_t>(slot)].generation, m_tag};
  m_joints.push_back(std::move(made.value()));
  m_jointIds.push_back(id);
  for (const BodyId body : ids)
    if (!body.isNull()) bodyRef(body).wake();
  m_maybeAsleep = true;
  return id;
}

Expected<bool> World::removeJoint(JointId id) {
  if (const std::string why = invalidJointReason(id); !why.empty()) return Error{"cannot remove: " + why};
  Slot& slot = m_jointSlots[static_cast<std::size_t>(id.index - 1)];
  const auto dense = static_cast<std::size_t>(slot.denseIndex);
  for (const BodyId body : {m_joints[dense].def.bodyA, m_joints[dense].def.bodyB})
    if (!body.isNull() && isValid(body)) bodyRef(body).wake();
  m_joints.erase(m_joints.begin() + static_cast<std::ptrdiff_t>(dense));
  m_jointIds.erase(m_jointIds.begin() + static_cast<std::ptrdiff_t>(dense));
  for (std::size_t i = dense; i < m_jointIds.size(); ++i)
    m_jointSlots[static_cast<std::size_t>(m_jointIds[i].index - 1)].denseIndex = static_cast<int32_t>(i);
  slot.denseIndex = -1;
  ++slot.generation;
  m_freeJointSlots.push_back(id.index - 1);
  return true;
}

Expected<bool> World::setJointMotor(JointId id, const JointMotor& motor) {
  if (const std::string why = invalidJointReason(id); !why.empty()) return Error{"cannot set the motor: " + why};
  JointConstraint& joint = m_joints[static_cast<std::size_t>(m_jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex)];
  if (motor.enabled && !joint.hasAxis()) return Error{"joint '" + joint.def.name + "': only revolute and prismatic joints take a motor"};
  if (motor.enabled && (!std::isfinite(motor.targetRate) || !std::isfinite(motor.maxEffort) || motor.maxEffort < 0.0))
    return Error{"joint '" + joint.def.name + "': the motor needs a finite target rate and a finite, non-negative max effort"};
  joint.def.motor = motor;
  if (motor.enabled) joint.def.drive.enabled = false;
  wakeJointBodies(joint.def);
  return true;
}

Expected<bool> World::setJointDrive(JointId id, const JointDrive& drive) {
  if (const std::string why = invalidJointReason(id); !why.empty()) return Error{"cannot set the drive: " + why};
  JointConstraint& joint = m_joints[static_cast<std::size_t>(m_jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex)];
  // A distance joint made with a spring takes a new rest length (the
  // drive's target) and gains; its drive is what it is, so it stays on.
  const bool spring = joint.hasSpring();
  if (spring && !drive.enabled)
    return Error{"joint '" + joint.def.name + "': a spring cannot be turned off (its drive is the spring)"};
  if (drive.enabled && !joint.hasAxis() && !spring)
    return Error{"joint '" + joint.def.name +
                 "': only revolute and prismatic joints take a drive (and distance joints made with a spring)"};
  if (drive.enabled) {
    if (const std::string why = invalidDriveReason(drive); !why.empty()) return Error{"joint '" + joint.def.name + "': " + why};
  }
  if (spring && drive.target < 0.0)
    return Error{"joint '" + joint.def.name + "': the spring's rest length must not be negative (got " +
                 std::to_string(drive.target) + ")"};
  joint.def.drive = drive;
  if (spring) joint.length = joint.def.length = drive.target;
  if (drive.enabled) joint.def.motor.enabled = false;
  wakeJointBodies(joint.def);
  return true;
}

Expected<bool> World::setJointEffort(JointId id, double effort) {
  if (const std::string why = invalidJointReason(id); !why.empty()) return Error{"cannot set the effort: " + why};
  JointConstraint& joint = m_joints[static_cast<std::size_t>(m_jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex)];
  if (!joint.hasAxis() && effort != 0.0) return Error{"joint '" + joint.def.name + "': only revolute and prismatic joints take an effort"};
  if (!std::isfinite(effort)) return Error{"joint '" + joint.def.name + "': the effort is not finite"};
  joint.def.effort = effort;
  wakeJointBodies(joint.def);
  return true;
}

void World::wakeJointBodies(const JointDef& def) {
  for (const BodyId body : {def.bodyA, def.bodyB})
    if (!body.isNull() && isValid(body)) bodyRef(body).wake();
  m_maybeAsleep = true;
}

std::vector<std::string> World::removeJointsOf(BodyId body) {
  std::vector<std::string> removed;
  for (std::size_t i = 0; i < m_joints.size();) {
    const JointDef& def = m_joints[i].def;
    if (def.bodyA != body && def.bodyB != body) {
      ++i;
      continue;
    }
    removed.push_back(def.name);
    (void)removeJoint(m_jointIds[i]);
  }
  return removed;
}

JointId World::findJoint(std::string_view name) const {
  for (std::size_t i = 0; i < m_joints.size(); ++i)
    if (m_joints[i].def.name == name) return m_jointIds[i];
  return {};
}

bool World::isValid(JointId id) const { return invalidJointReason(id).empty(); }

int World::jointCount() const { return static_cast<int>(m_joints.size()); }

JointId World::jointIdAt(int denseIndex) const { return m_jointIds[static_cast<std::size_t>(denseIndex)]; }

std::string World::invalidJointReason(JointId id) const {
  // As for bodies, the message is made only for an id that fails: a robot
  // client's joint commands and state reads look joints up every cycle.
  const auto named = [&] {
    return "joint id (index " + std::to_string(id.index) + ", generation " + std::to_string(id.generation) +
           ", world " + std::to_string(id.world) + ")";
  };
  if (id.isNull()) return "a null joint id";
  if (id.world != m_tag) return named() + " is of another world";
  if (id.index < 1 || static_cast<std::size_t>(id.index) > m_jointSlots.size())
    return named() + " names no slot of this world";
  const Slot& slot = m_jointSlots[static_cast<std::size_t>(id.index - 1)];
  if (slot.denseIndex < 0 || slot.generation != id.generation) return named() + " is stale: its joint was removed";
  return {};
}

bool World::jointIsEnforced(const JointConstraint& joint) const {
  for (const BodyId body : {joint.def.bodyA, joint.def.bodyB})
    if (!body.isNull() && m_bodies[denseIndexOf(body)].isFrozen()) return false;
  return true;
}

JointState World::jointState(JointId id) const {
  if (const std::string why = invalidJointReason(id); !why.empty()) throw std::invalid_argument(why);
  return jointStateAt(m_jointSlots[static_cast<std::size_t>(id.index - 1)].denseIndex);
}

JointState World::jointStateAt(int denseIndex) const {
  const JointConstraint& joint = m_joints[static_cast<std::size_t>(denseIndex)];
  JointState out;
  out.name = joint.def.name;
  out.type = joint.def.type;
  out.bodyA = joint.def.bodyA;
  out.bodyB = joint.def.bodyB;
  JointSidePose poses[2];
  Vec3 linear[2] = {Vec3::Zero(), Vec3::Zero()};
  Vec3 angular[2] = {Vec3::Zero(), Vec3::Zero()};
  const BodyId ids[2] = {joint.def.bodyA, joint.def.bodyB};
  for (int side = 0; side < 2; ++side) {
    if (ids[side].isNull()) continue;
    const Body& body = m_bodies[denseIndexOf(ids[side])];
    poses[side] = poseOfBody(body);
    linear[side] = body.linearVelocity();
    angular[side] = body.angularVelocity();
  }
  out.position = joint.coordinate(poses[0], poses[1]);
  out.rate = joint.coordinateRate(poses[0], poses[1], linear[0], angular[0], linear[1], angular[1]);
  out.anchorA = poses[0].position + poses[0].rotation * joint.anchorA;
  out.anchorB = poses[1].position + poses[1].rotation * joint.anchorB;
  out.axis = poses[0].rotation * joint.axisA;
  out.rotation = (poses[0].orientation.conjugate() * poses[1].orientation * joint.restRelative.conjugate()).normalized();
  double errors[kMaxJointRows];
  joint.errors(poses[0], poses[1], joint.basisAt(poses[0]), errors);
  for (int r = 0; r < joint.rowCount(); ++r) out.error = std::max(out.error, std::abs(errors[r]));
  if (joint.hasLimit()) {  // a bound passed counts as an error too
    out.error = std::max({out.error, joint.limitLower() - out.position, out.position - joint.limitUpper()});
  }
  out.force = joint.lastForce;
  out.torque = joint.lastTorque;
  out.axisEffort = joint.lastAxisEffort;
  out.atLimit = joint.lastAtLimit;
  out.active = jointIsEnforced(joint);
  return out;
}

const std::vector<BodyContact>& World::contactsBetweenUnjoinedBodies(const std::vector<BodyContact>& detected,
                                                                     std::vector<BodyContact>& storage) const {
  if (m_joints.empty() || detected.empty()) return detected;
  std::vector<std::pair<int, int>> joined;  // dense (lower, higher)
  for (const JointConstraint& joint : m_joints) {
    if (joint.def.collideConnected || joint.def.bodyA.isNull() || joint.def.bodyB.isNull()) continue;
    const int a = static_cast<int>(denseIndexOf(joint.def.bodyA));
    const int b = static_cast<int>(denseIndexOf(joint.def.bodyB));
    joined.emplace_back(std::min(a, b), std::max(a, b));
  }
  if (joined.empty()) return detected;
  std::sort(joined.begin(), joined.end());
  const auto isJoined = [&](const BodyContact& c) {
    return std::binary_search(joined.begin(), joined.end(),
                              std::make_pair(std::min(c.bodyA, c.bodyB), std::max(c.bodyA, c.bodyB)));
  };
  if (std::none_of(detected.begin(), detected.end(), isJoined)) return detected;
  storage.clear();
  for (const BodyContact& c : detected)
    if (!isJoined(c)) storage.push_back(c);
  return storage;
}

std::vector<char> World::findActuatedBodies() const {
  // A drive moves its joint until it settles; a body's own sleep thresholds
  // (cm/s) are too coarse for a servo creeping to its target, so a drive's
  // joint counts as moving down to this rate.
  constexpr double kDriveSettledRate = 1e-4;  // rad/s or m/s
  std::vector<char> busy;
  for (std::size_t j = 0; j < m_joints.size(); ++j) {
    const JointDef& def = m_joints[j].def;
    const bool motorMoves = def.motor.enabled && def.motor.targetRate != 0.0;
    if (!motorMoves && !def.drive.enabled) continue;
    if (!jointIsEnforced(m_joints[j])) continue;
    if (!motorMoves && std::abs(jointStateAt(static_cast<int>(j)).rate) <= kDriveSettledRate) continue;
    if (busy.empty()) busy.assign(m_bodies.size(), 0);
    for (const BodyId body : {def.bodyA, def.bodyB})
      if (!body.isNull()) busy[denseIndexOf(body)] = 1;
  }
  return busy;
}

std::vector<char> World::findJointedBodies() const {
  std::vector<char> jointed;
  for (const JointConstraint& joint : m_joints) {
    if (!jointIsEnforced(joint)) continue;
    for (const BodyId id : {joint.def.bodyA, joint.def.bodyB}) {
      if (id.isNull()) continue;
      const std::size_t i = denseIndexOf(id);
      const Body& body = m_bodies[i];
      if (body.isStatic() || body.isSleeping()) continue;
      if (jointed.empty()) jointed.assign(m_bodies.size(), 0);
      jointed[i] = 1;
    }
  }
  return jointed;
}

void World::collectJointLinks(const std::vector<int>& local, std::vector<JointLink>& links,
                              std::vector<std::size_t>& linkJoint) const {
  for (std::size_t j = 0; j < m_joints.size(); ++j) {
    const JointConstraint& joint = m_joints[j];
    if (!jointIsEnforced(joint)) continue;
    JointLink link;
    link.joint = &joint;
    bool anyMoving = false;
    for (const bool sideB : {false, true}) {
      const BodyId id = sideB ? joint.def.bodyB : joint.def.bodyA;
      int& index = sideB ? link.bodyB : link.bodyA;
      JointSidePose& fixed = sideB ? link.fixedB : link.fixedA;
      if (id.isNull()) continue;
      const std::size_t i = denseIndexOf(id);
      index = local[i];
      if (index < 0) fixed = poseOfBody(m_bodies[i]);  // static
      anyMoving = anyMoving || index >= 0;
    }
    if (!anyMoving) continue;
    links.push_back(link);
    linkJoint.push_back(j);
  }
}

std::unique_ptr<VelocityProjection> World::addJointedIslandsInContact(ContactStep& step,
                                                                      const std::vector<char>& jointed,
                                                                      const std::vector<int>& islandOf) const {
  const std::size_t n = m_bodies.size();
  std::vector<char> touching(n, 0);  // per island root
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!jointed[i] || !step.solving[i]) continue;
    touching[static_cast<std::size_t>(islandOf[i])] = 1;
    any = true;
  }
  if (!any) return nullptr;
  std::vector<int> local(n, -1);
  std::vector<std::size_t> solverIndex;
  std::vector<JointBody> bodies;
  for (std::size_t i = 0; i < n; ++i) {
    if (!jointed[i] || !touching[static_cast<std::size_t>(islandOf[i])]) continue;
    step.solving[i] = 1;
    const Body& body = m_bodies[i];
    local[i] = static_cast<int>(bodies.size());
    solverIndex.push_back(i);
    JointBody jb;
    jb.startPosition = body.position();
    jb.startOrientation = body.orientation();
    jb.startInverseInertia = body.inverseInertiaWorld();
    jb.inverseMass = body.inverseMass();
    bodies.push_back(jb);
  }
  std::vector<JointLink> links;
  std::vector<std::size_t> linkJoint;
  collectJointLinks(local, links, linkJoint);
  // Joints of islands that touch nothing have no side here: leave them out.
  std::vector<JointLink> inContact;
  for (const JointLink& link : links)
    if (link.bodyA >= 0 || link.bodyB >= 0) inContact.push_back(link);
  return std::make_unique<JointVelocityProjection>(inContact, bodies, std::move(solverIndex));
}

void World::stepJointedBodies(const std::vector<char>& jointed, const std::vector<char>& solving,
                              const std::vector<int>& islandOf, double h) {
  if (jointed.empty()) return;
  const std::size_t n = m_bodies.size();
  // Islands with a jointed body in contact take the semi-implicit step.
  std::vector<char> contactIsland;
  if (!solving.empty()) {
    contactIsland.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      if (jointed[i] && solving[i]) contactIsland[static_cast<std::size_t>(islandOf[i])] = 1;
  }
  // The jointed bodies: where they start, their momenta after the first
  // half kick (and the contact impulses, for those the contact solver
  // moved), the contact impulses alone, the split-impulse pseudo-velocities.
  std::vector<int> local(n, -1);
  std::vector<std::size_t> dense;
  std::vector<Momenta> kicked, contactImpulse;
  std::vector<Vec3> pseudoLinear, pseudoAngular;
  std::vector<char> staggered;  // per jointed body: RATTLE's half kicks (else the whole kick first)
  for (std::size_t i = 0; i < n; ++i) {
    if (!jointed[i]) continue;
    const Body& body = m_bodies[i];
    local[i] = static_cast<int>(dense.size());
    dense.push_back(i);
    const bool halves = contactIsland.empty() || !contactIsland[static_cast<std::size_t>(islandOf[i])];
    staggered.push_back(halves ? 1 : 0);
    const Momenta free =
        integrateMomenta(body.state(), body.rotation(), body.dynamics(), forcesOn(i), halves ? 0.5 * h : h);
    Momenta withContacts = free;
    Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
    if (!solving.empty() && solving[i]) {
      const SolverBody& sb = m_solverBodies[i];
      withContacts = {body.mass() * sb.linearVelocity, body.inertiaWorld() * sb.angularVelocity};
      linear = sb.pseudoLinear;
      angular = sb.pseudoAngular;
    }
    kicked.push_back(withContacts);
    contactImpulse.push_back({withContacts.linear - free.linear, withContacts.angular - free.angular});
    pseudoLinear.push_back(linear);
    pseudoAngular.push_back(angular);
  }
  std::vector<JointLink> links;
  std::vector<std::size_t> linkJoint;
  collectJointLinks(local, links, linkJoint);

  // The step in `parts` equal sub-steps, each a whole RATTLE step (half
  // kick, drift and projection, half kick, velocity projection); the
  // contact impulses and the pseudo-velocities' displacement go into the
  // first. Returns whether every projection converged.
  JointSolver& solver = *m_jointSolver;
  std::vector<RigidState> ends(dense.size());
  std::vector<Vec3> reactionLinear(links.size()), reactionAngular(links.size());
  // The direct efforts, as impulses along each joint's axis row over
  // `duration` at the current poses of `bodies` (start or end).
  const auto applyEfforts = [&](std::vector<JointBody>& bodies, bool atStart, double duration, bool staggeredPart) {
    for (const JointLink& link : links) {
      const double effort = appliedEffort(link.joint->def);
      if (effort == 0.0 || !link.joint->hasAxis()) continue;
      const int any = link.bodyA >= 0 ? link.bodyA : link.bodyB;
      if ((staggered[static_cast<std::size_t>(any)] != 0) != staggeredPart) continue;
      JointRow row;
      link.joint->axisRow(sidePose(link, bodies, false, atStart), sidePose(link, bodies, true, atStart), row);
      const double lambda = effort * duration;
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
  };
  std::vector<double> axisImpulse(links.size(), 0.0);
  std::vector<int> atLimit(links.size(), 0);
  const auto attempt = [&](int parts) {
    const double s = h / parts;
    std::fill(axisImpulse.begin(), axisImpulse.end(), 0.0);
    bool converged = true;
    std::fill(reactionLinear.begin(), reactionLinear.end(), Vec3::Zero());
    std::fill(reactionAngular.begin(), reactionAngular.end(), Vec3::Zero());
    for (std::size_t k = 0; k < dense.size(); ++k) ends[k] = m_bodies[dense[k]].state();
    for (int part = 0; part < parts; ++part) {
      std::vector<JointBody> bodies(dense.size());
      for (std::size_t k = 0; k < dense.size(); ++k) {
        const Body& body = m_bodies[dense[k]];
        const RigidState& start = ends[k];
        const Mat3 rotation = start.orientation.toRotationMatrix();
        JointBody& jb = bodies[k];
        jb.startPosition = start.position;
        jb.startOrientation = start.orientation;
        jb.startInverseInertia = rotatedDiagonal(rotation, body.dynamics().inverseInertiaBody);
        jb.inverseMass = body.inverseMass();
        Momenta momenta = kicked[k];
        if (parts > 1) {
          momenta = integrateMomenta(start, rotation, body.dynamics(), forcesOn(dense[k]), staggered[k] ? 0.5 * s : s);
          if (part == 0) {
            momenta.linear += contactImpulse[k].linear;
            momenta.angular += contactImpulse[k].angular;
          }
        }
        jb.linearMomentum = momenta.linear;
        jb.angularMomentum = momenta.angular;
        if (part == 0) {
          jb.pseudoLinear = static_cast<double>(parts) * pseudoLinear[k];
          jb.pseudoAngular = static_cast<double>(parts) * pseudoAngular[k];
        }
      }
      applyEfforts(bodies, true, 0.5 * s, true);  // RATTLE's first half kick
      applyEfforts(bodies, true, s, false);       // the whole kick of an island in contact
      std::vector<JointLinkResult> results;
      converged = solver.solvePositions(links, bodies, s, JointSolverSettings{}, results) && converged;
      // The second half kick at the end poses, then the velocities tangent
      // to the joints there.
      std::vector<Mat3> endInverseInertia(bodies.size());
      for (std::size_t k = 0; k < bodies.size(); ++k) {
        const Body& body = m_bodies[dense[k]];
        JointBody& jb = bodies[k];
        const RigidState state{jb.position, jb.orientation, jb.linearMomentum, jb.angularMomentum};
        const Mat3 rotation = state.orientation.toRotationMatrix();
        if (staggered[k]) {
          const Momenta end = integrateMomenta(state, rotation, body.dynamics(), forcesOn(dense[k]), 0.5 * s);
          jb.linearMomentum = end.linear;
          jb.angularMomentum = end.angular;
        }
        endInverseInertia[k] = rotatedDiagonal(rotation, body.dynamics().inverseInertiaBody);
      }
      applyEfforts(bodies, false, 0.5 * s, true);  // the second half kick
      solver.projectVelocities(links, bodies, endInverseInertia, s, results);
      for (std::size_t k = 0; k < bodies.size(); ++k)
        ends[k] = {bodies[k].position, bodies[k].orientation, bodies[k].linearMomentum, bodies[k].angularMomentum};
      for (std::size_t l = 0; l < links.size(); ++l) {
        reactionLinear[l] += results[l].linearImpulse;
        reactionAngular[l] += results[l].angularImpulse;
        axisImpulse[l] += results[l].axisImpulse;
        atLimit[l] = results[l].atLimit;
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
    Body& body = m_bodies[dense[k]];
    body.moveTo(ends[k]);
    noteSpeeds(body.linearVelocity().squaredNorm(), body.angularVelocity().squaredNorm());
  }
  for (std::size_t l = 0; l < links.size(); ++l) {
    JointConstraint& joint = m_joints[linkJoint[l]];
    joint.lastForce = reactionLinear[l] / h;
    joint.lastTorque = reactionAngular[l] / h;
    joint.lastAxisEffort = axisImpulse[l] / h + appliedEffort(joint.def);
    joint.lastAtLimit = atLimit[l];
  }
}

}  // namespace rbsim
