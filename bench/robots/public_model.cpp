#include "public_model.h"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include <utility>

#include "config/config_loader.h"
#include "inverse_diagonal.h"
#include "rbsim/physics/world.h"

namespace rbsim::bench::robots {

namespace {

[[noreturn]] void fail(const std::string& message) {
  std::fprintf(stderr, "public robots: %s\n", message.c_str());
  std::exit(1);
}

std::string list(const std::vector<double>& v) {
  std::ostringstream out;
  out.precision(17);
  out << "[";
  for (size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << v[i];
  out << "]";
  return out.str();
}

std::string list(const Vec3& v) {
  return list(std::vector<double>(v.begin(), v.end()));
}

std::string list(const Quat& q) {
  return list(std::vector<double>(q.begin(), q.end()));
}

}  // namespace

std::string publicWorldYaml(const PublicScene& s, const std::vector<JointGains>& gains,
                            bool selfCollisionKey) {
  std::ostringstream y;
  y.precision(17);
  y << "# bench/robots: scene " << s.name << " of the public robots' benchmark, written by\n"
    << "# the harness (public_model.cpp) from public_scenes.cpp.\n"
    << "world: {dt: " << s.dt << ", gravity: [0, 0, -9.81]}\n"
    << "contact: {friction: " << s.friction << "}\n"
    << "bodies:\n"
    << "  - name: ground\n"
    << "    shape: {type: plane, normal: [0, 0, 1], offset: 0}\n"
    << "    static: true\n";
  if (s.table) {
    y << "  - name: table\n"
      << "    shape: {type: box, half_extents: " << list(s.tableHalfExtents) << "}\n"
      << "    position: " << list(s.tableCenter) << "\n"
      << "    static: true\n";
  }
  for (const ObjectSpec& o : s.objects) {
    y << "  - name: " << o.name << "\n    shape: ";
    switch (o.kind) {
      case ObjectSpec::Kind::Box:
        y << "{type: box, half_extents: " << list(o.halfExtents) << "}\n";
        break;
      case ObjectSpec::Kind::Cylinder:
        y << "{type: cylinder, radius: " << o.radius << ", half_length: " << o.halfLength
          << "}\n";
        break;
      case ObjectSpec::Kind::Mesh:
        y << "{type: mesh, file: " << o.mesh << "}\n";
        break;
    }
    y << "    mass: " << o.mass << "\n"
      << "    position: " << list(o.pose.position) << "\n"
      << "    orientation: " << list(o.pose.orientation) << "\n";
  }
  y << "robots:\n"
    << "  - name: " << s.robot << "\n"
    << "    urdf: " << s.urdf << "\n"
    << "    position: " << list(s.base.position) << "\n"
    << "    orientation: " << list(s.base.orientation) << "\n"
    << "    fixed_base: " << (s.fixedBase ? "true" : "false") << "\n"
    << "    merge_fixed_links: true\n";
  if (selfCollisionKey) y << "    self_collision: " << (s.selfCollision ? "true" : "false") << "\n";
  y << "    joint_positions: {";
  for (size_t k = 0; k < s.joints.size(); ++k)
    y << (k ? ", " : "") << s.joints[k] << ": " << s.start[k];
  y << "}\n";
  if (!gains.empty()) {
    y << "    joint_drives:\n";
    for (size_t k = 0; k < s.joints.size(); ++k)
      y << "      " << s.joints[k] << ": {stiffness: " << gains[k].stiffness
        << ", damping: " << gains[k].damping << "}\n";
  }
  return y.str();
}

PublicWorld loadPublicWorld(const PublicScene& s, const std::vector<JointGains>& gains) {
  PublicWorld w;
  w.yaml = publicWorldYaml(s, gains, true);
  Expected<WorldDef> def = parseWorldConfig(w.yaml, s.name + ".yaml", "");
  if (!def.ok() && def.error().message.find("self_collision") != std::string::npos) {
    w.note =
        "this tree's loader does not know self_collision (" + def.error().message +
        "): the key is left out, and every pair of links not joined by a joint collides";
    w.yaml = publicWorldYaml(s, gains, false);
    def = parseWorldConfig(w.yaml, s.name + ".yaml", "");
  }
  if (!def.ok()) fail(def.error().message);
  w.def = std::move(*def);
  return w;
}

std::vector<JointGains> publicGains(const PublicScene& s) {
  const PublicWorld w = loadPublicWorld(s, {});
  const Expected<World> world = World::fromDef(w.def);
  if (!world.ok()) fail(world.error().message);
  // The robot's moving bodies and, for each, the joint that holds it to
  // its parent.
  struct Link {
    double mass;
    Vec3 inertia;  // principal moments
    Pose pose;     // centre of mass, principal axes
  };
  std::map<std::string, int, std::less<>> linkOf;
  std::vector<Link> links;
  for (const BodyDef& body : w.def.bodies) {
    if (body.isStatic || body.name.rfind(s.robot + "/", 0) != 0) continue;
    const BodyView view = world->body(world->findBody(body.name));
    const rbsim::Vec3& c = view.position();
    const Quaternion& q = view.orientation();
    const rbsim::Vec3 i = view.dynamics().inertiaBody;
    linkOf[body.name] = static_cast<int>(links.size());
    links.push_back({view.mass(), {i.x(), i.y(), i.z()}, {{c.x(), c.y(), c.z()}, {q.w, q.x, q.y, q.z}}});
  }
  struct Axis {
    int parentLink = -1;  // -1: a static body or the world
    bool prismatic = false;
    Vec3 anchor, axis;
    int driven = -1;  // index in s.joints, or -1
  };
  std::vector<Axis> axisOf(links.size());
  std::vector<bool> held(links.size(), false);
  for (const NamedJointDef& j : w.def.joints) {
    const auto child = linkOf.find(j.bodyB);
    if (child == linkOf.end()) continue;
    Axis& a = axisOf[static_cast<size_t>(child->second)];
    const auto parent = linkOf.find(j.bodyA);
    a.parentLink = parent == linkOf.end() ? -1 : parent->second;
    a.prismatic = j.def.type == JointType::Prismatic;
    const rbsim::Vec3 axis = j.def.axis.normalized();
    a.anchor = {j.def.anchor.x(), j.def.anchor.y(), j.def.anchor.z()};
    a.axis = {axis.x(), axis.y(), axis.z()};
    held[static_cast<size_t>(child->second)] = true;
    for (size_t k = 0; k < s.joints.size(); ++k)
      if (j.def.name == s.robot + "/" + s.joints[k]) a.driven = static_cast<int>(k);
  }
  // M = Σ over links of m Jvᵀ Jv + Jwᵀ I Jw over the driven joints above
  // each link (a floating root is held still: its links have no joint).
  const size_t n = s.joints.size();
  std::vector<double> m(n * n, 0.0);
  for (size_t i = 0; i < links.size(); ++i) {
    const Link& link = links[i];
    std::vector<std::pair<size_t, const Axis*>> above;
    for (int up = static_cast<int>(i); up >= 0 && held[static_cast<size_t>(up)];
         up = axisOf[static_cast<size_t>(up)].parentLink) {
      const Axis& a = axisOf[static_cast<size_t>(up)];
      if (a.driven >= 0) above.push_back({static_cast<size_t>(a.driven), &a});
    }
    const auto columns = [&](const Axis& a, Vec3& linear, Vec3& angular) {
      if (a.prismatic) {
        linear = a.axis;
        angular = {0, 0, 0};
      } else {
        linear = cross(a.axis, sub(link.pose.position, a.anchor));
        angular = rotate(conjugate(link.pose.orientation), a.axis);  // in the principal axes
      }
    };
    for (const auto& [k, a] : above) {
      Vec3 va, wa;
      columns(*a, va, wa);
      for (const auto& [l, b] : above) {
        Vec3 vb, wb;
        columns(*b, vb, wb);
        double rotational = 0;
        for (size_t d = 0; d < 3; ++d) rotational += link.inertia[d] * wa[d] * wb[d];
        m[k * n + l] += link.mass * dot(va, vb) + rotational;
      }
    }
  }
  for (size_t k = 0; k < n; ++k)
    if (!(m[k * n + k] > 0)) fail("scene " + s.name + ": joint " + s.joints[k] + " moves nothing");
  const std::vector<double> inverse = inverseDiagonal(std::move(m), n);
  const double omega = 2 * kPi * s.naturalFrequency;
  std::vector<JointGains> gains(n);
  for (size_t k = 0; k < n; ++k) {
    const double inertia = 1 / inverse[k];
    gains[k] = {inertia * omega * omega, 2 * s.dampingRatio * inertia * omega};
  }
  return gains;
}

RootInertial rootInertial(const PublicScene& s) {
  const PublicWorld w = loadPublicWorld(s, {});
  const Expected<World> world = World::fromDef(w.def);
  if (!world.ok()) fail(world.error().message);
  for (const BodyDef& body : w.def.bodies) {
    if (body.name.rfind(s.robot + "/", 0) != 0) continue;
    bool child = false;
    for (const NamedJointDef& j : w.def.joints) child = child || j.bodyB == body.name;
    if (child) continue;
    const BodyView view = world->body(world->findBody(body.name));
    const rbsim::Vec3& c = view.position();
    const Quaternion& q = view.orientation();
    const rbsim::Vec3 i = view.dynamics().inertiaBody;
    RootInertial r;
    r.mass = view.mass();
    r.centre = toLocal(s.base, {c.x(), c.y(), c.z()});
    r.axes = multiply(conjugate(s.base.orientation), {q.w, q.x, q.y, q.z});
    r.moments = {i.x(), i.y(), i.z()};
    return r;
  }
  fail("scene " + s.name + ": no root body");
}

}  // namespace rbsim::bench::robots
