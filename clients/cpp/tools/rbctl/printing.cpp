#include "printing.h"

namespace rbsim::rbctl {

namespace {

// 10 significant digits: readable, and enough to tell one step's velocity
// change from the next.
void printVector(std::FILE* out, const char* key, const double* values, int count) {
  std::fprintf(out, " %s", key);
  for (int i = 0; i < count; ++i) std::fprintf(out, " %.10g", values[i]);
}

}  // namespace

void printState(std::FILE* out, const rbsim::world_state_t& state, const std::string& body) {
  std::fprintf(out, "step %lld sim_time %.10g world_revision %lld bodies %d\n",
               static_cast<long long>(state.step), state.sim_time,
               static_cast<long long>(state.world_revision), state.total_bodies);
  for (const auto& b : state.bodies) {
    if (!body.empty() && b.name != body) continue;
    std::fprintf(out, "body %s id %d", b.name.c_str(), b.id);
    printVector(out, "position", b.position, 3);
    printVector(out, "orientation", b.orientation, 4);
    printVector(out, "linear_velocity", b.linear_velocity, 3);
    printVector(out, "angular_velocity", b.angular_velocity, 3);
    std::fputc('\n', out);
  }
}

void printStatus(std::FILE* out, const rbsim::status_t& s) {
  std::fprintf(out,
               "step %lld\nsim_time %.10g\nworld_revision %lld\ndt %.10g\npaused %s\n"
               "target_real_time_factor %.10g\nmeasured_real_time_factor %.10g\nwindow %.10g\n"
               "step_time_mean %.10g\nstep_time_worst %.10g\noverruns %lld\n"
               "commands_accepted %lld\ncommands_rejected %lld\nnum_bodies %d\n"
               "num_frozen_bodies %d\nnum_active_wrenches %d\nnum_contacts %d\n",
               static_cast<long long>(s.step), s.sim_time, static_cast<long long>(s.world_revision),
               s.dt, s.paused ? "true" : "false", s.target_real_time_factor,
               s.measured_real_time_factor, s.window, s.step_time_mean, s.step_time_worst,
               static_cast<long long>(s.overruns), static_cast<long long>(s.commands_accepted),
               static_cast<long long>(s.commands_rejected), s.num_bodies, s.num_frozen_bodies,
               s.num_active_wrenches, s.num_contacts);
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
    if (b.shape_type == "sphere") std::fprintf(out, " radius %.10g", b.radius);
    if (b.shape_type == "box") printVector(out, "half_extents", b.half_extents, 3);
    if (b.shape_type == "cylinder" || b.shape_type == "capsule")
      std::fprintf(out, " radius %.10g half_length %.10g", b.radius, b.half_length);
    if (b.shape_type == "plane") {
      printVector(out, "normal", b.plane_normal, 3);
      std::fprintf(out, " offset %.10g", b.plane_offset);
    }
    if (b.shape_type == "mesh")
      std::fprintf(out, " file %s vertices %d triangles %d", b.mesh_file.c_str(), b.num_vertices,
                   b.num_triangles);
    if (b.shape_type == "compound") {
      std::fprintf(out, " parts %d", b.num_parts);
      for (const auto& part : b.parts) std::fprintf(out, " %s", part.shape_type.c_str());
    }
    std::fputc('\n', out);
  }
}

}  // namespace rbsim::rbctl
