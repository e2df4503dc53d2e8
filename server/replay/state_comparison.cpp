#include "replay/state_comparison.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "rbsim/physics/types.h"

namespace rbsim {

namespace {

std::string exact(double value) { return exactText(value); }

template <std::size_t N>
std::string listOf(const double (&values)[N]) {
  std::string out = "[";
  for (std::size_t i = 0; i < N; ++i) out += (i ? ", " : "") + exact(values[i]);
  return out + "]";
}

// Bitwise, so that -0.0 differs from 0.0 and a NaN equals the same NaN.
template <std::size_t N>
bool sameBits(const double (&a)[N], const double (&b)[N]) {
  return std::memcmp(a, b, sizeof a) == 0;
}

template <std::size_t N>
double largestDifference(const double (&a)[N], const double (&b)[N]) {
  double largest = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    const double d = std::fabs(a[i] - b[i]);
    largest = std::isnan(d) ? d : std::max(largest, d);
  }
  return largest;
}

}  // namespace

std::optional<std::string> firstStateDifference(const rbsim::world_state_t& recorded,
                                                const rbsim::world_state_t& replayed) {
  const std::string atStep = "step " + std::to_string(recorded.step);
  const auto header = [&](const char* field, int64_t log, int64_t replay) -> std::optional<std::string> {
    if (log == replay) return std::nullopt;
    return atStep + ", page " + std::to_string(recorded.page) + ": " + field + " is " +
           std::to_string(log) + " in the log, " + std::to_string(replay) + " in the replay";
  };
  if (auto d = header("step", recorded.step, replayed.step)) return d;
  if (auto d = header("world_revision", recorded.world_revision, replayed.world_revision)) return d;
  if (auto d = header("num_pages", recorded.num_pages, replayed.num_pages)) return d;
  if (auto d = header("total_bodies", recorded.total_bodies, replayed.total_bodies)) return d;
  if (auto d = header("first_body_index", recorded.first_body_index, replayed.first_body_index)) return d;
  if (auto d = header("num_bodies", recorded.num_bodies, replayed.num_bodies)) return d;
  if (std::memcmp(&recorded.sim_time, &replayed.sim_time, sizeof(double)) != 0)
    return atStep + ": sim_time is " + exact(recorded.sim_time) + " s in the log, " +
           exact(replayed.sim_time) + " s in the replay";

  for (std::size_t i = 0; i < recorded.bodies.size() && i < replayed.bodies.size(); ++i) {
    const rbsim::body_state_t& log = recorded.bodies[i];
    const rbsim::body_state_t& replay = replayed.bodies[i];
    const std::string body = atStep + ", body '" + log.name + "' (id " + std::to_string(log.id) + ")";
    if (log.id != replay.id || log.name != replay.name)
      return body + ": the replay has body '" + replay.name + "' (id " + std::to_string(replay.id) +
             ") in its place";
    const auto compare = [&](const char* what, const char* unit, const auto& a,
                             const auto& b) -> std::optional<std::string> {
      if (sameBits(a, b)) return std::nullopt;
      return body + ": " + what + " differs by " + exact(largestDifference(a, b)) + " " + unit +
             ": log " + listOf(a) + ", replay " + listOf(b);
    };
    if (auto d = compare("position", "m", log.position, replay.position)) return d;
    if (auto d = compare("orientation", "(quaternion components)", log.orientation, replay.orientation))
      return d;
    if (auto d = compare("linear_velocity", "m/s", log.linear_velocity, replay.linear_velocity)) return d;
    if (auto d = compare("angular_velocity", "rad/s", log.angular_velocity, replay.angular_velocity))
      return d;
  }
  return std::nullopt;
}

std::optional<std::string> firstJointsDifference(const rbsim::joints_t& recorded,
                                                 const rbsim::joints_t& replayed) {
  const std::string atStep = "step " + std::to_string(recorded.step);
  const auto header = [&](const char* field, int64_t log, int64_t replay) -> std::optional<std::string> {
    if (log == replay) return std::nullopt;
    return atStep + ", joints page " + std::to_string(recorded.page) + ": " + field + " is " +
           std::to_string(log) + " in the log, " + std::to_string(replay) + " in the replay";
  };
  if (auto d = header("step", recorded.step, replayed.step)) return d;
  if (auto d = header("world_revision", recorded.world_revision, replayed.world_revision)) return d;
  if (auto d = header("num_pages", recorded.num_pages, replayed.num_pages)) return d;
  if (auto d = header("total_joints", recorded.total_joints, replayed.total_joints)) return d;
  if (auto d = header("first_joint_index", recorded.first_joint_index, replayed.first_joint_index)) return d;
  if (auto d = header("num_joints", recorded.num_joints, replayed.num_joints)) return d;
  if (std::memcmp(&recorded.sim_time, &replayed.sim_time, sizeof(double)) != 0)
    return atStep + ": the joints' sim_time is " + exact(recorded.sim_time) + " s in the log, " +
           exact(replayed.sim_time) + " s in the replay";

  for (std::size_t i = 0; i < recorded.joints.size() && i < replayed.joints.size(); ++i) {
    const rbsim::joint_state_t& log = recorded.joints[i];
    const rbsim::joint_state_t& replay = replayed.joints[i];
    const std::string joint = atStep + ", joint '" + log.name + "'";
    if (log.name != replay.name) return joint + ": the replay has joint '" + replay.name + "' in its place";
    const auto compare = [&](const char* what, const char* unit, const auto& a,
                             const auto& b) -> std::optional<std::string> {
      if (sameBits(a, b)) return std::nullopt;
      return joint + ": " + what + " differs by " + exact(largestDifference(a, b)) + " " + unit +
             ": log " + listOf(a) + ", replay " + listOf(b);
    };
    const double logScalars[4] = {log.position, log.rate, log.effort, log.error};
    const double replayScalars[4] = {replay.position, replay.rate, replay.effort, replay.error};
    if (auto d = compare("(position, rate, effort, error)", "(rad or m, per s, N·m or N, m or rad)",
                         logScalars, replayScalars))
      return d;
    if (auto d = compare("rotation", "(quaternion components)", log.rotation, replay.rotation)) return d;
    if (auto d = compare("force", "N", log.force, replay.force)) return d;
    if (auto d = compare("torque", "N·m", log.torque, replay.torque)) return d;
    if (log.at_limit != replay.at_limit || log.active != replay.active)
      return joint + ": at_limit/active are " + std::to_string(log.at_limit) + "/" +
             std::to_string(log.active) + " in the log, " + std::to_string(replay.at_limit) + "/" +
             std::to_string(replay.active) + " in the replay";
  }
  return std::nullopt;
}

}  // namespace rbsim
