// bench_robots_lockstep: how many lock-step control cycles a C++ client gets
// through rbserver over LCM on config/worlds/robot_arm.yaml (issue 37). One
// cycle: command all seven joints, have the paused server take one step,
// wait for the state of that step. The paths, each timed in the same run
// against the same server:
//
//   robot         rbsim::client::Robot: one robot_command_t (steps = 1), its
//                 ack, the robot_state_t of the step; the Robot's connection
//                 decodes ROBOT_STATE and ACK only.
//   robot-client  the same messages through a Client's connection, which also
//                 decodes every world state, joints_t and status: what a Robot
//                 built on Client would pay.
//   joints        the per-joint path of before: seven joint_command_t, a
//                 command_t STEP 1, its ack, then the joints_t of the step.
//
// Every path holds the arm where it stands with position drives (the world
// file's gains), so the runs are alike. Per path it prints
//   ROW | path | cycles | cycles/s | p50 us | p99 us | max us | client cpu us |
// with the round trip of a cycle from its first send to the state it waits
// for, and the client thread's CPU time per cycle (which shows what decoding
// everything costs a Client, and which the machine's load does not inflate);
// and for the robot path a BREAKDOWN line: the medians of the time to the
// server's ack, from the ack to the state's publication, and from there to
// the client (the messages' utimes against the wall clock).
//
//   bench_robots_lockstep [--url URL] [--prefix P] [--robot arm] [--cycles 2000]
//                         [--warmup 200] [--paths robot,robot-client,joints]
// against a server started on robot_arm.yaml (bench/robots/run_lockstep.sh
// starts one in a private network namespace and runs this three times).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <functional>
#include <optional>
#include <rbsim/robot_command_t.hpp>
#include <rbsim/robot_state_t.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rbsim/client/client.h"
#include "rbsim/client/robot.h"

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

namespace {

constexpr double kStiffness = 2000.0;  // N·m/rad, robot_arm.yaml's joint_drives
constexpr double kDamping = 100.0;     // N·m·s/rad

struct Options {
  rbsim::client::ClientOptions client;
  std::string robot = "arm";
  int cycles = 2000;
  int warmup = 200;
  std::vector<std::string> paths = {"robot", "robot-client", "joints"};
};

// The client's own CPU time (its thread: sending, receiving, decoding,
// waiting in poll), which other processes on the machine do not inflate as
// they do the wall clock.
double cpuMicros() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) * 1e6 + static_cast<double>(now.tv_nsec) * 1e-3;
}

int64_t wallMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

// The physics' share of a cycle as the server reports it: status_t (1–10
// Hz) of the newest window that the client handled during the run just timed.
void printServerStepTime(const std::string& path, rbsim::client::Client& client) {
  const auto& status = client.latestStatus();
  if (!status) return;
  std::printf("SERVER | %s | step_time_mean %.1f us | step_time_worst %.1f us |\n", path.c_str(),
              status->step_time_mean * 1e6, status->step_time_worst * 1e6);
}

// For a cycle that cannot go on: says why, returns false.
bool failed(const std::string& why) {
  std::fprintf(stderr, "bench_robots_lockstep: %s\n", why.c_str());
  return false;
}

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "bench_robots_lockstep: %s\n", what.c_str());
  std::exit(3);
}

// Times `cycle` (which returns false when it could not complete) `cycles`
// times after `warmup` untimed ones, and prints the ROW.
void measure(const std::string& path, const Options& options, const std::function<bool()>& cycle) {
  for (int i = 0; i < options.warmup; ++i)
    if (!cycle()) fail(path + ": a warm-up cycle failed");
  std::vector<double> micros;
  micros.reserve(options.cycles);
  const auto start = Clock::now();
  const double cpuStart = cpuMicros();
  for (int i = 0; i < options.cycles; ++i) {
    const auto begin = Clock::now();
    if (!cycle()) fail(path + ": cycle " + std::to_string(i) + " failed");
    micros.push_back(std::chrono::duration<double, std::micro>(Clock::now() - begin).count());
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const double cpuPerCycle = (cpuMicros() - cpuStart) / options.cycles;
  std::sort(micros.begin(), micros.end());
  const auto at = [&](double fraction) {
    return micros[std::min(micros.size() - 1, static_cast<std::size_t>(fraction * micros.size()))];
  };
  std::printf("ROW | %s | %d | %.0f | %.1f | %.1f | %.1f | %.1f |\n", path.c_str(), options.cycles,
              options.cycles / seconds, at(0.50), at(0.99), micros.back(), cpuPerCycle);
  std::fflush(stdout);
}

void benchRobot(const Options& options) {
  rbsim::client::Robot robot(options.robot, options.client);
  if (!robot.waitForState(5s)) fail(robot.lastError());
  if (!robot.pause()) fail(robot.lastError());
  const int n = robot.numJoints();
  const Eigen::VectorXd hold = robot.q(), zero = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd kp = Eigen::VectorXd::Constant(n, kStiffness);
  const Eigen::VectorXd kd = Eigen::VectorXd::Constant(n, kDamping);
  // Where a cycle's time goes, from the wall clock (one host, one clock):
  // until the server's ack (its utime: when it took the command), from the
  // ack to the state (its utime: when it was published: the step and the
  // states published before it), from the state to the client having it.
  std::vector<double> toAck, toState, toClient;
  measure("robot", options, [&] {
    const int64_t sent = wallMicros();
    if (!robot.command(hold, zero, zero, kp, kd) || !robot.stepSync(1, 2s))
      return failed(robot.lastError());
    const int64_t received = wallMicros();
    const int64_t acked = robot.lastAck()->utime, published = robot.state()->utime;
    toAck.push_back(static_cast<double>(acked - sent));
    toState.push_back(static_cast<double>(published - acked));
    toClient.push_back(static_cast<double>(received - published));
    return true;
  });
  std::printf("BREAKDOWN | robot | to the ack p50 %.0f us | ack to state p50 %.0f us | "
              "state to client p50 %.0f us |\n",
              median(toAck), median(toState), median(toClient));
}

// The robot path over a Client's connection: the same two messages a cycle,
// but every message the server publishes is decoded (world state pages,
// joints, status) as a Client does.
void benchRobotOverClient(const Options& options) {
  rbsim::client::Client client(options.client);
  std::optional<rbsim::robot_state_t> state;
  struct Handler {
    std::optional<rbsim::robot_state_t>* state;
    const std::string* robot;
    void onState(const lcm::ReceiveBuffer*, const std::string&, const rbsim::robot_state_t* s) {
      if (s->robot == *robot) *state = *s;
    }
  } handler{&state, &options.robot};
  client.lcm().subscribe(client.channel("ROBOT_STATE"), &Handler::onState, &handler);
  if (!client.spinUntil([&] { return state.has_value(); }, 5s)) fail("no robot state");
  if (const auto ack = client.waitForAck(client.pause(), 2s); !ack || !ack->accepted) fail("pause");
  const int n = state->num_joints;
  rbsim::robot_command_t message;
  message.client = client.clientId();
  message.robot = options.robot;
  message.apply_at_step = -1;
  message.num_joints = n;
  message.num_names = 0;
  message.mode.assign(n, rbsim::robot_command_t::MODE_POSITION);
  message.position = state->position;
  message.velocity.assign(n, 0.0);
  message.effort.assign(n, 0.0);
  message.stiffness.assign(n, kStiffness);
  message.damping.assign(n, kDamping);
  message.max_effort.assign(n, 0.0);
  message.state_rate = 0.0;
  message.state_dynamics = -1;
  message.steps = 1;
  int64_t seq = 1'000'000'000;  // apart from the Client's own numbers
  measure("robot-client", options, [&] {
    message.utime = 0;
    message.seq = ++seq;
    if (client.lcm().publish(client.channel("ROBOT_COMMAND"), &message) != 0)
      return failed("could not publish");
    const auto ack = client.waitForAck(seq, rbsim::client::AckKind::RobotCommand, 2s);
    if (!ack) return failed("no ack of the robot command");
    if (!ack->accepted) return failed("robot command refused: " + ack->reason);
    return client.spinUntil([&] { return state->step >= ack->effective_step; }, 2s);
  });
  printServerStepTime("robot-client", client);
}

void benchJoints(const Options& options) {
  rbsim::client::Client client(options.client);
  if (!client.spinUntil([&] { return client.latestJoints().has_value(); }, 5s)) fail("no joints");
  if (const auto ack = client.waitForAck(client.pause(), 2s); !ack || !ack->accepted) fail("pause");
  std::vector<rbsim::client::JointCommand> commands;
  for (const auto& joint : client.latestJoints()->joints) {
    if (!joint.name.starts_with(options.robot + "/")) continue;
    rbsim::client::JointCommand command;
    command.joint = joint.name;
    command.mode = rbsim::client::JointMode::Position;
    command.target = joint.position;
    command.stiffness = kStiffness;
    command.damping = kDamping;
    commands.push_back(command);
  }
  measure("joints", options, [&] {
    for (const auto& command : commands)
      if (!client.commandJoint(command).sent) return failed("could not publish a joint command");
    const auto ack = client.waitForAck(client.step(1), 2s);
    if (!ack) return failed("no ack of STEP");
    if (!ack->accepted) return failed("STEP refused: " + ack->reason);
    return client.spinUntil(
        [&] { return client.latestJoints() && client.latestJoints()->step >= ack->effective_step; },
        2s);
  });
  printServerStepTime("joints", client);
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (i + 1 >= argc) fail("usage: see the comment at the top of bench/robots/lockstep.cpp");
    const std::string value = argv[++i];
    if (flag == "--url")
      options.client.url = value;
    else if (flag == "--prefix")
      options.client.channelPrefix = value;
    else if (flag == "--robot")
      options.robot = value;
    else if (flag == "--cycles")
      options.cycles = std::stoi(value);
    else if (flag == "--warmup")
      options.warmup = std::stoi(value);
    else if (flag == "--paths") {
      options.paths.clear();
      std::stringstream list(value);
      for (std::string path; std::getline(list, path, ',');) options.paths.push_back(path);
    } else
      fail("unknown option " + flag);
  }
  std::printf("CFG | robot %s | cycles %d | warmup %d |\n", options.robot.c_str(), options.cycles,
              options.warmup);
  std::printf("ROW | path | cycles | cycles/s | p50 us | p99 us | max us | client cpu us |\n");
  for (const std::string& path : options.paths) {
    if (path == "robot")
      benchRobot(options);
    else if (path == "robot-client")
      benchRobotOverClient(options);
    else if (path == "joints")
      benchJoints(options);
    else
      fail("unknown path " + path);
  }
  return 0;
}
