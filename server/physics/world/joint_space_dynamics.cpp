#include "rbsim/physics/joint_space_dynamics.h"

#include <algorithm>
#include <map>
#include <optional>

#include "rbsim/physics/body_view.h"
#include "rbsim/physics/joint_definition.h"
#include "rbsim/physics/world.h"

namespace rbsim {

Expected<JointSpaceDynamics> JointSpaceDynamics::ofRobot(const World& world, std::string_view prefix) {
  const std::string robot = "robot '" + std::string(prefix) + "…'";
  // The robot's joints, and the one that carries each of its bodies.
  struct Carried {
    int joint;         // dense index
    std::string parent;  // "" for the world
  };
  std::map<std::string, Carried, std::less<>> carrier;  // by child body name
  std::vector<std::string> children;                   // in the world's joint order
  for (int j = 0; j < world.jointCount(); ++j) {
    const JointDef& def = world.jointDefinitionAt(j);
    if (def.name.compare(0, prefix.size(), prefix) != 0) continue;
    if (def.type != JointType::Revolute && def.type != JointType::Prismatic && def.type != JointType::Fixed)
      return Error{robot + ": joint '" + def.name + "' is " + jointTypeName(def.type) +
                   ": joint-space dynamics take revolute, prismatic and fixed joints"};
    if (!world.jointStateAt(j).active)
      return Error{robot + ": joint '" + def.name + "' is not enforced (one of its bodies is frozen)"};
    if (def.bodyB.isNull()) return Error{robot + ": joint '" + def.name + "' carries the world (body_b): not a tree"};
    const std::string child = world.body(def.bodyB).name();
    const std::string parent = def.bodyA.isNull() ? std::string() : world.body(def.bodyA).name();
    if (!carrier.emplace(child, Carried{j, parent}).second)
      return Error{robot + ": body '" + child + "' is moved by two of its joints ('" +
                   world.jointDefinitionAt(carrier.at(child).joint).name + "' and '" + def.name + "'): not a tree"};
    children.push_back(child);
  }
  if (children.empty()) return Error{robot + ": the world has no joint named so"};

  JointSpaceDynamics out;
  out.m_gravity = world.settings().gravity;
  // The base: the parent no joint of the robot carries (the world: "").
  // One that moves floats, and must be free: held by no other joint.
  std::optional<std::string> base;
  for (const std::string& child : children) {
    const std::string& parent = carrier.at(child).parent;
    if (carrier.count(parent) != 0) continue;
    if (base && *base != parent)
      return Error{robot + ": two bases, '" + (base->empty() ? "the world" : *base) + "' and '" +
                   (parent.empty() ? "the world" : parent) + "': not one tree"};
    base = parent;
  }
  if (!base) return Error{robot + ": its joints close a loop: not a tree"};
  const BodyId baseId = base->empty() ? BodyId{} : world.findBody(*base);
  if (!baseId.isNull() && !world.body(baseId).isStatic()) {
    for (int j = 0; j < world.jointCount(); ++j) {
      const JointDef& def = world.jointDefinitionAt(j);
      const bool ours = def.name.compare(0, prefix.size(), prefix) == 0;
      if (!ours && (def.bodyA == baseId || def.bodyB == baseId))
        return Error{robot + ": its base '" + *base + "' moves and is held by joint '" + def.name +
                     "', which is not the robot's: a floating base must be free"};
    }
    const BodyView body = world.body(baseId);
    out.m_floating = true;
    out.m_baseName = *base;
    out.m_baseOrigin = body.bodyToWorld(body.description().shapeTranslation);
    Link link;
    link.name = *base;
    link.anchor = out.m_baseOrigin;
    link.center = body.position();
    link.mass = body.mass();
    link.inertia = body.inertiaWorld();
    out.m_links.push_back(link);
  }
  // Parents before children: a body is placed once its parent is (or the
  // parent is the base: the world, a static body).
  std::map<std::string, int, std::less<>> linkOf;
  if (out.m_floating) linkOf.emplace(out.m_baseName, 0);
  std::vector<char> placed(children.size(), 0);
  for (std::size_t round = 0; round < children.size(); ++round) {
    bool progress = false;
    for (std::size_t k = 0; k < children.size(); ++k) {
      if (placed[k]) continue;
      const Carried& carried = carrier.at(children[k]);
      const JointDef& def = world.jointDefinitionAt(carried.joint);
      int parent = -1;
      if (!carried.parent.empty()) {
        const auto link = linkOf.find(carried.parent);
        if (link != linkOf.end()) {
          parent = link->second;
        } else if (carrier.count(carried.parent)) {
          continue;  // its parent is the robot's and not placed yet
        }
      }
      const JointState state = world.jointStateAt(carried.joint);
      const BodyView body = world.body(def.bodyB);
      Link link;
      link.name = children[k];
      link.parent = parent;
      link.prismatic = def.type == JointType::Prismatic;
      link.axis = state.axis;
      link.anchor = state.anchorA;
      link.center = body.position();
      link.mass = body.mass();
      link.inertia = body.inertiaWorld();
      if (def.type != JointType::Fixed) link.coordinate = 0;  // numbered below, in joint order
      linkOf.emplace(link.name, static_cast<int>(out.m_links.size()));
      out.m_links.push_back(link);
      placed[k] = 1;
      progress = true;
    }
    if (!progress) break;
  }
  if (std::find(placed.begin(), placed.end(), 0) != placed.end())
    return Error{robot + ": its joints close a loop: not a tree"};
  // Coordinates in the world's joint order, after a floating base's six.
  const int first = out.m_floating ? 6 : 0;
  for (const std::string& child : children) {
    Link& link = out.m_links[static_cast<std::size_t>(linkOf.at(child))];
    if (link.coordinate < 0) continue;
    const int joint = carrier.at(child).joint;
    link.coordinate = first + static_cast<int>(out.m_jointNames.size());
    out.m_jointNames.push_back(world.jointDefinitionAt(joint).name);
  }
  const auto n = static_cast<Eigen::Index>(out.m_jointNames.size());
  out.m_q.resize(n);
  out.m_qd.resize(first + n);
  if (out.m_floating) {
    const BodyView body = world.body(baseId);
    out.m_qd.head<3>() = body.velocityAtPoint(out.m_baseOrigin);
    out.m_qd.segment<3>(3) = body.angularVelocity();
  }
  for (const Link& link : out.m_links) {
    if (link.coordinate < 0) continue;
    const JointState state = world.jointStateAt(carrier.at(link.name).joint);
    out.m_q[link.coordinate - first] = state.position;
    out.m_qd[link.coordinate] = state.rate;
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
