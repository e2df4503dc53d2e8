#include "printing.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <utility>

namespace rbsim::rbctl {

namespace {

using nlohmann::json;

// Below this a quaternion component is rounding noise of a unit quaternion,
// beyond what 10 significant digits of the others can show: printed as 0.
constexpr double kQuaternionNoise = 1e-12;

std::array<double, 4> cleanOrientation(const double* q) {
  std::array<double, 4> out{};
  for (int i = 0; i < 4; ++i) out[i] = std::abs(q[i]) < kQuaternionNoise ? 0.0 : q[i];
  return out;
}

// An empty text field as a word, so that every line keeps two fields.
const char* orNone(const std::string& text) {
  return text.empty() ? "none" : text.c_str();
}

bool selected(const std::vector<std::string>& bodies, const std::string& name) {
  return bodies.empty() || std::find(bodies.begin(), bodies.end(), name) != bodies.end();
}

template <std::size_t N>
json array(const double (&values)[N]) {
  return json(std::vector<double>(std::begin(values), std::end(values)));
}

// 10 significant digits: readable, and enough to tell one step's velocity
// change from the next.
void printVector(std::FILE* out, const char* key, const double* values, int count) {
  std::fprintf(out, " %s", key);
  for (int i = 0; i < count; ++i) std::fprintf(out, " %.10g", values[i]);
}

// A revolute's or prismatic's numbers that are set (not 0): where its
// coordinate's zero is, its actuator's limits, its own losses.
void printAxisExtras(std::FILE* out, const rbsim::joint_description_t& j) {
  const std::pair<const char*, double> extras[] = {{"initial_position", j.initial_position},
                                                   {"effort_limit", j.effort_limit},
                                                   {"rate_limit", j.rate_limit},
                                                   {"damping", j.damping},
                                                   {"friction", j.friction}};
  for (const auto& [label, value] : extras)
    if (value != 0.0) std::fprintf(out, " %s %.10g", label, value);
}

}  // namespace

void printState(std::FILE* out, const rbsim::world_state_t& state,
                const std::vector<std::string>& bodies) {
  std::fprintf(out, "step %lld sim_time %.10g world_revision %lld bodies %d\n",
               static_cast<long long>(state.step), state.sim_time,
               static_cast<long long>(state.world_revision), state.total_bodies);
  for (const auto& b : state.bodies) {
    if (!selected(bodies, b.name)) continue;
    std::fprintf(out, "body %s id %d", b.name.c_str(), b.id);
    printVector(out, "position", b.position, 3);
    printVector(out, "orientation", cleanOrientation(b.orientation).data(), 4);
    printVector(out, "linear_velocity", b.linear_velocity, 3);
    printVector(out, "angular_velocity", b.angular_velocity, 3);
    if (!b.frozen.empty()) std::fprintf(out, " frozen %s", b.frozen.c_str());
    std::fputc('\n', out);
  }
}

void printStatus(std::FILE* out, const rbsim::status_t& s) {
  std::fprintf(out,
               "step %lld\nsim_time %.10g\nworld_revision %lld\ndt %.10g\npaused %s\n"
               "target_real_time_factor %.10g\nmeasured_real_time_factor %.10g\nwindow %.10g\n"
               "step_time_mean %.10g\nstep_time_worst %.10g\noverruns %lld\n"
               "commands_accepted %lld\ncommands_rejected %lld\nnum_bodies %d\n"
               "num_frozen_bodies %d\nnum_active_wrenches %d\nnum_contacts %d\n"
               "instance_id %s\nother_instance_id %s\nnum_sleeping_bodies %d\n",
               static_cast<long long>(s.step), s.sim_time, static_cast<long long>(s.world_revision),
               s.dt, s.paused ? "true" : "false", s.target_real_time_factor,
               s.measured_real_time_factor, s.window, s.step_time_mean, s.step_time_worst,
               static_cast<long long>(s.overruns), static_cast<long long>(s.commands_accepted),
               static_cast<long long>(s.commands_rejected), s.num_bodies, s.num_frozen_bodies,
               s.num_active_wrenches, s.num_contacts, orNone(s.instance_id),
               orNone(s.other_instance_id), s.num_sleeping_bodies);
}

void printWorld(std::FILE* out, const rbsim::world_t& world) {
  std::fprintf(out, "world_revision %lld step %lld dt %.10g integrator %s bodies %d",
               static_cast<long long>(world.world_revision), static_cast<long long>(world.step),
               world.dt, world.integrator.c_str(), world.total_bodies);
  printVector(out, "gravity", world.gravity, 3);
  std::fputc('\n', out);
  for (const auto& b : world.bodies) {
    std::fprintf(out, "body %s id %d shape %s static %s mass %.10g", b.name.c_str(), b.id,
                 b.shape_type.c_str(), b.is_static ? "true" : "false", b.mass);
    printVector(out, "inertia", b.inertia, 3);
    std::fprintf(out, " mass_properties %s", b.mass_properties_given ? "given" : "computed");
    if (b.shape_type == "sphere") std::fprintf(out, " radius %.10g", b.radius);
    if (b.shape_type == "box") printVector(out, "half_extents", b.half_extents, 3);
    if (b.shape_type == "cylinder" || b.shape_type == "capsule")
      std::fprintf(out, " radius %.10g half_length %.10g", b.radius, b.half_length);
    if (b.shape_type == "plane") {
      printVector(out, "normal", b.plane_normal, 3);
      std::fprintf(out, " offset %.10g", b.plane_offset);
    }
    if (b.shape_type == "mesh" || b.shape_type == "trimesh")
      std::fprintf(out, " file %s vertices %d triangles %d", b.mesh_file.c_str(), b.num_vertices,
                   b.num_triangles);
    if (b.shape_type == "compound") {
      std::fprintf(out, " parts %d", b.num_parts);
      for (const auto& part : b.parts) std::fprintf(out, " %s", part.shape_type.c_str());
    }
    if (!b.collides) std::fprintf(out, " collides false");
    // How it is drawn (a robot link's URDF visuals), when it says.
    if (b.num_visuals > 0) {
      std::fprintf(out, " visuals %d", b.num_visuals);
      for (const auto& visual : b.visuals) std::fprintf(out, " %s", visual.kind.c_str());
    }
    // The defaults (group 1, every bit of the mask) go unsaid.
    if (b.collision_group != 1 || b.collision_mask != 0xFFFFFFFFLL)
      std::fprintf(out, " collision_group %lld collision_mask %lld", static_cast<long long>(b.collision_group),
                   static_cast<long long>(b.collision_mask));
    if (!b.frozen.empty()) std::fprintf(out, " frozen %s", b.frozen.c_str());
    std::fputc('\n', out);
  }
}

void printJoints(std::FILE* out, const rbsim::world_t& world, const rbsim::joints_t* joints) {
  std::fprintf(out, "joints %d step %lld world_revision %lld\n", world.total_joints,
               static_cast<long long>(joints != nullptr ? joints->step : world.step),
               static_cast<long long>(world.world_revision));
  for (const auto& j : world.joints) {
    std::fprintf(out, "joint %s type %s body_a %s body_b %s", j.name.c_str(), j.type.c_str(),
                 j.body_a.c_str(), j.body_b.c_str());
    printVector(out, "axis", j.axis, 3);
    if (j.limit_enabled) {
      std::fprintf(out, " limits %.10g %.10g", j.lower_limit, j.upper_limit);
    } else {
      std::fprintf(out, " limits none");
    }
    if (j.type == "distance" && (!j.limit_enabled || j.spring)) std::fprintf(out, " length %.10g", j.length);
    if (j.spring) std::fprintf(out, " spring");
    if (j.type == "spherical" && j.cone_angle > 0.0) std::fprintf(out, " cone %.10g", j.cone_angle);
    printAxisExtras(out, j);
    const rbsim::joint_state_t* state = nullptr;
    if (joints != nullptr)
      for (const auto& candidate : joints->joints)
        if (candidate.name == j.name) state = &candidate;
    if (state != nullptr)
      std::fprintf(out, " position %.10g rate %.10g effort %.10g at_limit %d active %s", state->position,
                   state->rate, state->effort, state->at_limit, state->active ? "true" : "false");
    std::fputc('\n', out);
  }
}

void printRobotState(std::FILE* out, const rbsim::robot_state_t& s, bool dynamics) {
  std::fprintf(out, "robot %s step %lld sim_time %.10g world_revision %lld joints %d\n",
               s.robot.c_str(), static_cast<long long>(s.step), s.sim_time,
               static_cast<long long>(s.world_revision), s.num_joints);
  for (int i = 0; i < s.num_joints; ++i) {
    std::fprintf(out, "joint %s position %.10g velocity %.10g effort %.10g",
                 s.joint_names[i].c_str(), s.position[i], s.velocity[i], s.effort[i]);
    // A mimic follower: its leader moves it.
    if (s.leader[i] >= 0 && s.leader[i] < s.num_joints)
      std::fprintf(out, " leader %s", s.joint_names[s.leader[i]].c_str());
    std::fputc('\n', out);
  }
  std::fprintf(out, "base %s fixed %s", s.base.c_str(), s.base_fixed ? "true" : "false");
  printVector(out, "position", s.base_position, 3);
  printVector(out, "orientation", cleanOrientation(s.base_orientation).data(), 4);
  printVector(out, "linear_velocity", s.base_linear_velocity, 3);
  printVector(out, "angular_velocity", s.base_angular_velocity, 3);
  std::fputc('\n', out);
  if (!dynamics) return;
  std::fprintf(out, "dynamics dofs %d links %d", s.num_dofs, s.num_links);
  if (!s.dynamics_note.empty()) std::fprintf(out, " note %s", s.dynamics_note.c_str());
  std::fputc('\n', out);
  for (std::size_t i = 0; i < s.mass_matrix.size(); ++i) {
    std::fprintf(out, "mass_matrix %zu", i);
    for (const double v : s.mass_matrix[i]) std::fprintf(out, " %.10g", v);
    std::fputc('\n', out);
  }
  if (s.num_dofs > 0) {
    std::fprintf(out, "bias");
    for (const double v : s.bias) std::fprintf(out, " %.10g", v);
    std::fprintf(out, "\ngravity");
    for (const double v : s.gravity) std::fprintf(out, " %.10g", v);
    std::fputc('\n', out);
  }
  for (int i = 0; i < s.num_links; ++i) {
    std::fprintf(out, "link %s", s.link_names[i].c_str());
    printVector(out, "position", s.link_position[i].data(), 3);
    printVector(out, "orientation", cleanOrientation(s.link_orientation[i].data()).data(), 4);
    std::fputc('\n', out);
  }
}

void printRobotStateJson(std::FILE* out, const rbsim::robot_state_t& s, bool dynamics) {
  json document = {{"step", s.step},
                   {"sim_time", s.sim_time},
                   {"world_revision", s.world_revision},
                   {"robot", s.robot},
                   {"num_joints", s.num_joints},
                   {"joint_names", s.joint_names},
                   {"leader", s.leader},
                   {"position", s.position},
                   {"velocity", s.velocity},
                   {"effort", s.effort},
                   {"base", s.base},
                   {"base_position", array(s.base_position)},
                   {"base_orientation", cleanOrientation(s.base_orientation)},
                   {"base_linear_velocity", array(s.base_linear_velocity)},
                   {"base_angular_velocity", array(s.base_angular_velocity)},
                   {"base_fixed", static_cast<bool>(s.base_fixed)}};
  if (dynamics) {
    json orientations = json::array();
    for (const auto& q : s.link_orientation) orientations.push_back(cleanOrientation(q.data()));
    document["num_dofs"] = s.num_dofs;
    document["dynamics_note"] = s.dynamics_note;
    document["mass_matrix"] = s.mass_matrix;
    document["bias"] = s.bias;
    document["gravity"] = s.gravity;
    document["num_links"] = s.num_links;
    document["link_names"] = s.link_names;
    document["link_position"] = s.link_position;
    document["link_orientation"] = orientations;
    document["link_jacobian"] = s.link_jacobian;
  }
  std::fprintf(out, "%s\n", document.dump(-1, ' ', false, json::error_handler_t::replace).c_str());
}

void printStateJson(std::FILE* out, const rbsim::world_state_t& state,
                    const std::vector<std::string>& bodies) {
  json list = json::array();
  for (const auto& b : state.bodies) {
    if (!selected(bodies, b.name)) continue;
    list.push_back({{"id", b.id},
                    {"name", b.name},
                    {"position", array(b.position)},
                    {"orientation", cleanOrientation(b.orientation)},
                    {"linear_velocity", array(b.linear_velocity)},
                    {"angular_velocity", array(b.angular_velocity)},
                    {"frozen", b.frozen}});
  }
  const json document = {{"step", state.step},
                         {"sim_time", state.sim_time},
                         {"world_revision", state.world_revision},
                         {"bodies", list}};
  std::fprintf(out, "%s\n", document.dump(-1, ' ', false, json::error_handler_t::replace).c_str());
}

void printStatusJson(std::FILE* out, const rbsim::status_t& s) {
  const json document = {{"step", s.step},
                         {"sim_time", s.sim_time},
                         {"world_revision", s.world_revision},
                         {"dt", s.dt},
                         {"paused", s.paused},
                         {"target_real_time_factor", s.target_real_time_factor},
                         {"measured_real_time_factor", s.measured_real_time_factor},
                         {"window", s.window},
                         {"step_time_mean", s.step_time_mean},
                         {"step_time_worst", s.step_time_worst},
                         {"overruns", s.overruns},
                         {"commands_accepted", s.commands_accepted},
                         {"commands_rejected", s.commands_rejected},
                         {"num_bodies", s.num_bodies},
                         {"num_frozen_bodies", s.num_frozen_bodies},
                         {"num_active_wrenches", s.num_active_wrenches},
                         {"num_contacts", s.num_contacts},
                         {"instance_id", s.instance_id},
                         {"other_instance_id", s.other_instance_id},
                         {"num_sleeping_bodies", s.num_sleeping_bodies}};
  std::fprintf(out, "%s\n", document.dump(-1, ' ', false, json::error_handler_t::replace).c_str());
}

void printJointsJson(std::FILE* out, const rbsim::world_t& world, const rbsim::joints_t* joints) {
  json list = json::array();
  for (const auto& j : world.joints) {
    json entry = {{"name", j.name},
                  {"type", j.type},
                  {"body_a", j.body_a},
                  {"body_b", j.body_b},
                  {"anchor_a", array(j.anchor_a)},
                  {"anchor_b", array(j.anchor_b)},
                  {"axis", array(j.axis)},
                  {"limit_enabled", static_cast<bool>(j.limit_enabled)},
                  {"lower_limit", j.lower_limit},
                  {"upper_limit", j.upper_limit},
                  {"length", j.length},
                  {"spring", static_cast<bool>(j.spring)},
                  {"cone_angle", j.cone_angle},
                  {"initial_position", j.initial_position},
                  {"effort_limit", j.effort_limit},
                  {"rate_limit", j.rate_limit},
                  {"damping", j.damping},
                  {"friction", j.friction}};
    const rbsim::joint_state_t* state = nullptr;
    if (joints != nullptr)
      for (const auto& candidate : joints->joints)
        if (candidate.name == j.name) state = &candidate;
    if (state != nullptr) {
      entry["position"] = state->position;
      entry["rate"] = state->rate;
      entry["rotation"] = array(state->rotation);
      entry["force"] = array(state->force);
      entry["torque"] = array(state->torque);
      entry["effort"] = state->effort;
      entry["at_limit"] = state->at_limit;
      entry["error"] = state->error;
      entry["active"] = static_cast<bool>(state->active);
    }
    list.push_back(entry);
  }
  const json document = {{"step", joints != nullptr ? joints->step : world.step},
                         {"world_revision", world.world_revision},
                         {"joints", list}};
  std::fprintf(out, "%s\n", document.dump(-1, ' ', false, json::error_handler_t::replace).c_str());
}

void printWorldJson(std::FILE* out, const rbsim::world_t& world) {
  json list = json::array();
  for (const auto& b : world.bodies)
    list.push_back({{"id", b.id},
                    {"name", b.name},
                    {"shape", b.shape_type},
                    {"static", b.is_static},
                    {"mass", b.mass},
                    {"inertia", array(b.inertia)},
                    {"mass_properties_given", b.mass_properties_given},
                    {"collides", b.collides},
                    {"collision_group", b.collision_group},
                    {"collision_mask", b.collision_mask},
                    {"frozen", b.frozen}});
  const json document = {{"world_revision", world.world_revision},
                         {"step", world.step},
                         {"dt", world.dt},
                         {"integrator", world.integrator},
                         {"gravity", array(world.gravity)},
                         {"bodies", list}};
  std::fprintf(out, "%s\n", document.dump(-1, ' ', false, json::error_handler_t::replace).c_str());
}

namespace {

template <class Message>
void printSensorHeader(std::FILE* out, const Message& m, const char* type) {
  std::fprintf(out, "sensor %s type %s step %lld sim_time %.10g", m.name.c_str(), type,
               static_cast<long long>(m.step), m.sim_time);
}

// A scan: its pattern, how many beams returned, the nearest and farthest
// return, and every range (and hit body) when there are at most 16.
void printScan(std::FILE* out, const rbsim::range_scan_t& m) {
  constexpr int kListedRanges = 16;
  int returns = 0;
  double nearest = INFINITY, farthest = -INFINITY;
  for (const float range : m.ranges) {
    if (!std::isfinite(range)) continue;
    ++returns;
    nearest = std::min(nearest, static_cast<double>(range));
    farthest = std::max(farthest, static_cast<double>(range));
  }
  if (returns == 0) nearest = farthest = INFINITY;
  std::fprintf(out, " body %s", m.body.c_str());
  printVector(out, "position", m.position, 3);
  printVector(out, "orientation", cleanOrientation(m.orientation).data(), 4);
  std::fprintf(out, " beams %d samples %d returns %d nearest %.10g farthest %.10g", m.beams, m.horizontal_samples,
               returns, nearest, farthest);
  if (m.num_ranges <= kListedRanges) {
    std::fprintf(out, " ranges");
    for (const float range : m.ranges) std::fprintf(out, " %.10g", static_cast<double>(range));
    if (m.num_hit_bodies > 0) {
      std::fprintf(out, " hit_bodies");
      for (const std::string& body : m.hit_bodies) std::fprintf(out, " %s", body.empty() ? "-" : body.c_str());
    }
  }
}

}  // namespace

void printSensor(std::FILE* out, const client::SensorMessage& message) {
  if (const auto* m = std::get_if<rbsim::imu_t>(&message)) {
    printSensorHeader(out, *m, "imu");
    std::fprintf(out, " body %s", m->body.c_str());
    printVector(out, "linear_acceleration", m->linear_acceleration, 3);
    printVector(out, "angular_velocity", m->angular_velocity, 3);
    printVector(out, "orientation", cleanOrientation(m->orientation).data(), 4);
  } else if (const auto* c = std::get_if<rbsim::contact_sensor_t>(&message)) {
    printSensorHeader(out, *c, "contact");
    std::fprintf(out, " body %s", c->body.c_str());
    printVector(out, "force", c->force, 3);
    printVector(out, "torque", c->torque, 3);
    std::fprintf(out, " contacts %d", c->num_contacts);
  } else if (const auto* f = std::get_if<rbsim::force_torque_t>(&message)) {
    printSensorHeader(out, *f, "force_torque");
    std::fprintf(out, " joint %s body %s", f->joint.c_str(), f->body.c_str());
    printVector(out, "force", f->force, 3);
    printVector(out, "torque", f->torque, 3);
  } else if (const auto* r = std::get_if<rbsim::range_scan_t>(&message)) {
    printSensorHeader(out, *r, "range_scan");
    printScan(out, *r);
  }
  std::fprintf(out, "\n");
}

}  // namespace rbsim::rbctl
