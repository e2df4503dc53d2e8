#include "rbsim/physics/joint_space_dynamics.h"

#include <algorithm>
#include <optional>

#include "rbsim/physics/body_view.h"
#include "rbsim/physics/joint_definition.h"
#include "rbsim/physics/world.h"

namespace rbsim {

Expected<JointSpaceDynamics> JointSpaceDynamics::ofRobot(const World& world, std::string_view prefix) {
  // Called each control cycle (robot_state_t with its dynamics), so the
  // world is read once per joint and bodies are matched by id, not name:
  // reading the model costs about what computing M, h and J does.
  const auto robot = [&] { return "robot '" + std::string(prefix) + "…'"; };
  const auto nameOf = [&](BodyId id) { return id.isNull() ? std::string("the world") : world.body(id).name(); };
  // The robot's joints in the world's order, each with the body it carries.
  struct Carried {
    int joint = 0;  // dense index
    BodyId child, parent;  // parent null: the world
    JointState state;
    bool robotsParent = false;  // the parent is carried by another of the robot's joints
  };
  std::vector<Carried> carried;
  for (int j = 0; j < world.jointCount(); ++j) {
    const JointDef& def = world.jointDefinitionAt(j);
    if (def.name.compare(0, prefix.size(), prefix) != 0) continue;
    if (def.type != JointType::Revolute && def.type != JointType::Prismatic && def.type != JointType::Fixed)
      return Error{robot() + ": joint '" + def.name + "' is " + jointTypeName(def.type) +
                   ": joint-space dynamics take revolute, prismatic and fixed joints"};
    if (def.bodyB.isNull()) return Error{robot() + ": joint '" + def.name + "' carries the world (body_b): not a tree"};
    Carried next{j, def.bodyB, def.bodyA, world.jointStateAt(j)};
    if (!next.state.active)
      return Error{robot() + ": joint '" + def.name + "' is not enforced (one of its bodies is frozen)"};
    for (const Carried& other : carried)
      if (other.child == next.child)
        return Error{robot() + ": body '" + nameOf(next.child) + "' is moved by two of its joints ('" +
                     world.jointDefinitionAt(other.joint).name + "' and '" + def.name + "'): not a tree"};
    carried.push_back(std::move(next));
  }
  if (carried.empty()) return Error{robot() + ": the world has no joint named so"};

  JointSpaceDynamics out;
  out.m_gravity = world.settings().gravity;
  // The base: the parent no joint of the robot carries (or the world). One
  // that moves floats, and must be free: held by no other joint.
  std::optional<BodyId> base;
  for (Carried& c : carried) {
    c.robotsParent = std::any_of(carried.begin(), carried.end(), [&](const Carried& o) { return o.child == c.parent; });
    if (c.robotsParent) continue;
    if (base && !(*base == c.parent))
      return Error{robot() + ": two bases, '" + nameOf(*base) + "' and '" + nameOf(c.parent) + "': not one tree"};
    base = c.parent;
  }
  if (!base) return Error{robot() + ": its joints close a loop: not a tree"};
  if (!base->isNull() && !world.body(*base).isStatic()) {
    for (int j = 0; j < world.jointCount(); ++j) {
      const JointDef& def = world.jointDefinitionAt(j);
      const bool ours = def.name.compare(0, prefix.size(), prefix) == 0;
      if (!ours && (def.bodyA == *base || def.bodyB == *base))
        return Error{robot() + ": its base '" + nameOf(*base) + "' moves and is held by joint '" + def.name +
                     "', which is not the robot's: a floating base must be free"};
    }
    const BodyView body = world.body(*base);
    out.m_floating = true;
    out.m_baseName = body.name();
    out.m_baseOrigin = body.bodyToWorld(body.description().shapeTranslation);
    Link link;
    link.name = out.m_baseName;
    link.anchor = out.m_baseOrigin;
    link.center = body.position();
    link.mass = body.mass();
    link.inertia = body.inertiaWorld();
    out.m_links.push_back(link);
  }

  // Parents before children: a body is placed once its parent is (or the
  // parent is the base).
  std::vector<BodyId> linkBodies;  // the body of each link
  if (out.m_floating) linkBodies.push_back(*base);
  std::vector<int> linkOfCarried(carried.size(), -1);
  for (std::size_t round = 0; round < carried.size(); ++round) {
    bool progress = false;
    for (std::size_t k = 0; k < carried.size(); ++k) {
      if (linkOfCarried[k] >= 0) continue;
      const Carried& c = carried[k];
      int parent = -1;
      if (c.robotsParent || out.m_floating) {
        const auto at = std::find(linkBodies.begin(), linkBodies.end(), c.parent);
        if (at == linkBodies.end()) continue;  // its parent is not placed yet
        parent = static_cast<int>(at - linkBodies.begin());
      }
      const JointDef& def = world.jointDefinitionAt(c.joint);
      const BodyView body = world.body(c.child);
      Link link;
      link.name = body.name();
      link.parent = parent;
      link.prismatic = def.type == JointType::Prismatic;
      link.axis = c.state.axis;
      link.anchor = c.state.anchorA;
      link.center = body.position();
      link.mass = body.mass();
      link.inertia = body.inertiaWorld();
      if (def.type != JointType::Fixed) link.coordinate = 0;  // numbered below, in joint order
      linkOfCarried[k] = static_cast<int>(out.m_links.size());
      linkBodies.push_back(c.child);
      out.m_links.push_back(std::move(link));
      progress = true;
    }
    if (!progress) break;
  }
  if (std::find(linkOfCarried.begin(), linkOfCarried.end(), -1) != linkOfCarried.end())
    return Error{robot() + ": its joints close a loop: not a tree"};

  // Coordinates in the world's joint order, after a floating base's six.
  const int first = out.m_floating ? 6 : 0;
  int joints = 0;
  for (std::size_t k = 0; k < carried.size(); ++k)
    if (out.m_links[static_cast<std::size_t>(linkOfCarried[k])].coordinate >= 0) ++joints;
  out.m_q.resize(joints);
  out.m_qd.resize(first + joints);
  out.m_jointNames.reserve(static_cast<std::size_t>(joints));
  if (out.m_floating) {
    const BodyView body = world.body(*base);
    out.m_qd.head<3>() = body.velocityAtPoint(out.m_baseOrigin);
    out.m_qd.segment<3>(3) = body.angularVelocity();
  }
  for (std::size_t k = 0; k < carried.size(); ++k) {
    Link& link = out.m_links[static_cast<std::size_t>(linkOfCarried[k])];
    if (link.coordinate < 0) continue;
    const auto index = static_cast<Eigen::Index>(out.m_jointNames.size());
    link.coordinate = first + static_cast<int>(index);
    out.m_jointNames.push_back(world.jointDefinitionAt(carried[k].joint).name);
    out.m_q[index] = carried[k].state.position;
    out.m_qd[link.coordinate] = carried[k].state.rate;
  }
  return out;
}

Eigen::VectorXd JointSpaceDynamics::newtonEuler(const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                                double gravityScale) const {
  const std::size_t count = m_links.size();
  // Forward: each body's angular velocity and acceleration and its centre
  // of mass's acceleration, from its parent's through its joint.
  std::vector<Vec3> omega(count), alpha(count), accel(count);
  for (std::size_t b = 0; b < count; ++b) {
    const Link& link = m_links[b];
    if (m_floating && b == 0) {
      // The floating base: its origin's acceleration and its angular
      // velocity and acceleration are coordinates.
      const Vec3 r = link.center - link.anchor;
      omega[0] = qd.segment<3>(3);
      alpha[0] = qdd.segment<3>(3);
      accel[0] = qdd.head<3>() + alpha[0].cross(r) + omega[0].cross(omega[0].cross(r));
      continue;
    }
    Vec3 w = Vec3::Zero(), dw = Vec3::Zero(), a = Vec3::Zero(), parentCenter = link.anchor;
    if (link.parent >= 0) {
      const auto p = static_cast<std::size_t>(link.parent);
      w = omega[p];
      dw = alpha[p];
      a = accel[p];
      parentCenter = m_links[p].center;
    }
    const double rate = link.coordinate >= 0 ? qd[link.coordinate] : 0.0;
    const double acceleration = link.coordinate >= 0 ? qdd[link.coordinate] : 0.0;
    if (link.prismatic || link.coordinate < 0) {
      // Carried by the parent, sliding along the axis the parent carries.
      const Vec3 r = link.center - parentCenter;
      const Vec3 slide = link.axis * rate;
      omega[b] = w;
      alpha[b] = dw;
      accel[b] = a + dw.cross(r) + w.cross(w.cross(r)) + 2.0 * w.cross(slide) + link.axis * acceleration;
    } else {
      // Turning about the axis through the anchor, which the parent carries.
      const Vec3 toAnchor = link.anchor - parentCenter;
      const Vec3 d = link.center - link.anchor;
      omega[b] = w + link.axis * rate;
      alpha[b] = dw + w.cross(link.axis * rate) + link.axis * acceleration;
      accel[b] = a + dw.cross(toAnchor) + w.cross(w.cross(toAnchor)) + alpha[b].cross(d) +
                 omega[b].cross(omega[b].cross(d));
    }
  }
  // Backward: the wrench each joint passes to its subtree, about its anchor.
  std::vector<Vec3> force(count, Vec3::Zero()), moment(count, Vec3::Zero());
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(qd.size());
  for (std::size_t b = count; b-- > 0;) {
    const Link& link = m_links[b];
    const Vec3 f = link.mass * (accel[b] - gravityScale * m_gravity);
    const Vec3 n = link.inertia * alpha[b] + omega[b].cross(link.inertia * omega[b]);
    force[b] += f;
    moment[b] += n + (link.center - link.anchor).cross(f);
    if (link.coordinate >= 0) tau[link.coordinate] = link.prismatic ? link.axis.dot(force[b]) : link.axis.dot(moment[b]);
    if (m_floating && b == 0) {
      // The whole robot's wrench, about the base frame's origin.
      tau.head<3>() = force[0];
      tau.segment<3>(3) = moment[0];
    }
    if (link.parent >= 0) {
      const auto p = static_cast<std::size_t>(link.parent);
      force[p] += force[b];
      moment[p] += moment[b] + (link.anchor - m_links[p].anchor).cross(force[b]);
    }
  }
  return tau;
}

Eigen::VectorXd JointSpaceDynamics::biasForces() const {
  return newtonEuler(m_qd, Eigen::VectorXd::Zero(m_qd.size()), 1.0);
}

Eigen::VectorXd JointSpaceDynamics::gravityTorques() const {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m_qd.size());
  return newtonEuler(zero, zero, 1.0);
}

Eigen::VectorXd JointSpaceDynamics::inverseDynamics(const Eigen::VectorXd& qdd) const {
  return newtonEuler(m_qd, qdd, 1.0);
}

void JointSpaceDynamics::pointJacobian(int link, const Vec3& point, Eigen::MatrixXd& out) const {
  out.setZero(6, m_qd.size());
  if (m_floating) {
    // Every body rides on the base: v = v_o + ω × (p − o), ω = ω_base.
    out.block<3, 3>(0, 0).setIdentity();
    const Vec3 r = point - m_baseOrigin;
    Mat3 cross;
    cross << 0.0, r.z(), -r.y(), -r.z(), 0.0, r.x(), r.y(), -r.x(), 0.0;  // ω ↦ ω × r
    out.block<3, 3>(0, 3) = cross;
    out.block<3, 3>(3, 3).setIdentity();
  }
  for (int at = link; at >= 0; at = m_links[static_cast<std::size_t>(at)].parent) {
    const Link& joint = m_links[static_cast<std::size_t>(at)];
    if (joint.coordinate < 0) continue;
    if (joint.prismatic) {
      out.block<3, 1>(0, joint.coordinate) = joint.axis;
    } else {
      out.block<3, 1>(0, joint.coordinate) = joint.axis.cross(point - joint.anchor);
      out.block<3, 1>(3, joint.coordinate) = joint.axis;
    }
  }
}

Eigen::MatrixXd JointSpaceDynamics::massMatrix() const {
  // Σ over the bodies of J_vᵀ m J_v + J_ωᵀ I J_ω, J of the centre of mass.
  const Eigen::Index n = m_qd.size();
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd jacobian;
  for (std::size_t b = 0; b < m_links.size(); ++b) {
    const Link& link = m_links[b];
    pointJacobian(static_cast<int>(b), link.center, jacobian);
    const auto linear = jacobian.topRows<3>();
    const auto angular = jacobian.bottomRows<3>();
    mass.noalias() += link.mass * linear.transpose() * linear;
    mass.noalias() += angular.transpose() * link.inertia * angular;
  }
  return mass;
}

Expected<Eigen::MatrixXd> JointSpaceDynamics::jacobian(std::string_view body, const Vec3& worldPoint) const {
  Eigen::MatrixXd out;
  for (std::size_t b = 0; b < m_links.size(); ++b)
    if (m_links[b].name == body) {
      pointJacobian(static_cast<int>(b), worldPoint, out);
      return out;
    }
  return Error{"jacobian: body '" + std::string(body) + "' is not one of the robot's (its bodies: " +
               [&] {
                 std::string names;
                 for (const Link& link : m_links) names += (names.empty() ? "" : ", ") + link.name;
                 return names;
               }() +
               ")"};
}

std::vector<std::string> JointSpaceDynamics::bodyNames() const {
  std::vector<std::string> names;
  for (const Link& link : m_links) names.push_back(link.name);
  return names;
}

}  // namespace rbsim
