#include "verbs.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>
#include <rbsim/robot_command_t.hpp>
#include <rbsim/robot_state_t.hpp>
#include <rbsim/wrench_t.hpp>
#include <set>
#include <string_view>
#include <utility>

#include "printing.h"
#include "rbsim/client/lookup.h"
#include "rbsim/client/robot.h"

namespace rbsim::rbctl {

namespace {

using client::Client;

double seconds(Client::Timeout timeout) {
  return static_cast<double>(timeout.count()) * 1e-3;
}

// The distance of a and b ignoring ASCII case, or anything above `bound`
// once it is sure to exceed it (a row's smallest entry never shrinks).
std::size_t boundedDistance(std::string_view a, std::string_view b, std::size_t bound) {
  const auto lower = [](char c) { return std::tolower(static_cast<unsigned char>(c)); };
  const std::size_t gap = a.size() > b.size() ? a.size() - b.size() : b.size() - a.size();
  if (gap > bound) return bound + 1;
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    std::size_t smallest = row[0];
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min(
          {above + 1, row[j - 1] + 1, diagonal + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1)});
      diagonal = above;
      smallest = std::min(smallest, row[j]);
    }
    if (smallest > bound) return bound + 1;
  }
  return row[b.size()];
}

// " (did you mean 'a', 'b' or 'c'?)" with up to three of `known` within
// max(2, length / 3) edits of `name` ignoring case, closest first, ties
// alphabetically, or "": the server's rule for its refusals
// (server/bridge/closest_names.cpp) and the Python CLI's.
std::string didYouMean(const std::string& name, std::vector<std::string> known) {
  constexpr std::size_t kMaxSuggestedNameLength = 128;  // a guess at a longer one tells little
  if (name.size() > kMaxSuggestedNameLength) return "";
  const std::size_t bound = std::max<std::size_t>(2, name.size() / 3);
  std::sort(known.begin(), known.end());
  known.erase(std::unique(known.begin(), known.end()), known.end());
  std::vector<std::pair<std::size_t, std::string>> near;
  for (const std::string& candidate : known) {
    const std::size_t distance = boundedDistance(name, candidate, bound);
    if (distance <= bound) near.emplace_back(distance, candidate);
  }
  std::sort(near.begin(), near.end());
  if (near.size() > 3) near.resize(3);
  if (near.empty()) return "";
  std::string text = " (did you mean ";
  for (std::size_t i = 0; i < near.size(); ++i) {
    if (i > 0) text += i + 1 == near.size() ? " or " : ", ";
    text += "'" + near[i].second + "'";
  }
  return text + "?)";
}

int noAnswer(const Context& context, const std::string& what) {
  std::fprintf(stderr,
               "rbctl: no %s within %.3g s (is rbserver running on URL '%s' with channel prefix "
               "'%s'?)\n",
               what.c_str(), seconds(context.timeout), context.client.url().c_str(),
               context.client.channelPrefix().c_str());
  return kExitNoAnswer;
}

// Waits for the ack of `request` and reports it; `what` names the request.
int report(Context& context, const client::Request& request, const std::string& what,
           std::optional<rbsim::ack_t>* ackOut = nullptr) {
  const auto ack = context.client.waitForAck(request, context.timeout);
  if (ackOut != nullptr) *ackOut = ack;
  if (!ack) return noAnswer(context, "acknowledgement of " + what);
  if (!ack->accepted) {
    std::fprintf(stderr, "rbctl: %s rejected: %s\n", what.c_str(), ack->reason.c_str());
    return kExitRejected;
  }
  std::printf("%s accepted: effective_step %lld", what.c_str(),
              static_cast<long long>(ack->effective_step));
  if (ack->kind == rbsim::ack_t::KIND_WRENCH &&
      (ack->request == rbsim::wrench_t::MODE_CLEAR ||
       ack->request == rbsim::wrench_t::MODE_CLEAR_ALL_CLIENTS))
    std::printf(" cleared %d", ack->wrenches_cleared);
  if (!ack->reason.empty()) std::printf(" note %s", ack->reason.c_str());
  std::printf("\n");
  return kExitOk;
}

std::string readAll(std::FILE* file) {
  std::string text;
  char buffer[4096];
  std::size_t read;
  while ((read = std::fread(buffer, 1, sizeof buffer, file)) > 0) text.append(buffer, read);
  return text;
}

bool waitForState(Context& context) {
  return context.client.spinUntil([&] { return context.client.latestState().has_value(); },
                                  context.timeout);
}

// Reads the only option of status, bodies and joints; true with --json.
bool jsonOption(Arguments& arguments, const char* verb) {
  bool json = false;
  while (!arguments.empty()) {
    const std::string option = arguments.next(verb, "an option");
    if (option != "--json") throw UsageError(std::string(verb) + ": unknown option '" + option + "'");
    json = true;
  }
  return json;
}

int runState(Context& context, Arguments& arguments) {
  std::vector<std::string> bodies;
  bool json = false;
  while (!arguments.empty()) {
    const std::string option = arguments.next("state", "an option");
    if (option == "--body") {
      bodies.push_back(arguments.next(option, "a body name"));
    } else if (option == "--json") {
      json = true;
    } else {
      throw UsageError("state: unknown option '" + option + "'");
    }
  }
  if (!waitForState(context))
    return noAnswer(context, "state on " + context.client.channel("STATE"));
  const auto& state = *context.client.latestState();
  for (const std::string& body : bodies) {
    if (client::findBody(state, body) == nullptr) {
      std::vector<std::string> known;
      for (const auto& b : state.bodies) known.push_back(b.name);
      std::fprintf(stderr, "rbctl: no body named '%s' in the state of step %lld%s\n", body.c_str(),
                   static_cast<long long>(state.step), didYouMean(body, known).c_str());
      return kExitRejected;
    }
  }
  if (json) {
    printStateJson(stdout, state, bodies);
  } else {
    printState(stdout, state, bodies);
  }
  return kExitOk;
}

int runStatus(Context& context, Arguments& arguments) {
  const bool json = jsonOption(arguments, "status");
  if (!context.client.spinUntil([&] { return context.client.latestStatus().has_value(); },
                                context.timeout))
    return noAnswer(context, "status on " + context.client.channel("STATUS"));
  if (json) {
    printStatusJson(stdout, *context.client.latestStatus());
  } else {
    printStatus(stdout, *context.client.latestStatus());
  }
  return kExitOk;
}

int runBodies(Context& context, Arguments& arguments) {
  const bool json = jsonOption(arguments, "bodies");
  // Ask for a fresh description rather than wait for the next change.
  context.client.publishWorld();
  if (!context.client.spinUntil([&] { return context.client.world().has_value(); },
                                context.timeout))
    return noAnswer(context, "world description on " + context.client.channel("WORLD"));
  if (json) {
    printWorldJson(stdout, *context.client.world());
  } else {
    printWorld(stdout, *context.client.world());
  }
  return kExitOk;
}

int runSensor(Context& context, Arguments& arguments) {
  std::string name;
  int64_t count = 1;
  while (!arguments.empty()) {
    const std::string argument = arguments.next("sensor", "a sensor name");
    if (argument == "--count") {
      count = arguments.nextInteger(argument);
      if (count < 1) throw UsageError("sensor: --count must be at least 1");
    } else if (!argument.empty() && argument[0] == '-') {
      throw UsageError("sensor: unknown option '" + argument + "'");
    } else if (name.empty()) {
      name = argument;
    } else {
      throw UsageError("sensor: one sensor name, got '" + name + "' and '" + argument + "'");
    }
  }
  if (name.empty()) throw UsageError("sensor: expected a sensor name");
  client::SensorReader reader(context.client, name);
  int64_t printed = 0;
  reader.onReading([&](const client::SensorMessage& message) {
    if (printed >= count) return;
    printSensor(stdout, message);
    ++printed;
  });
  if (!context.client.spinUntil([&] { return printed >= count; }, context.timeout))
    return noAnswer(context, std::to_string(count - printed) + " more reading(s) on " + reader.channel());
  std::fflush(stdout);
  return kExitOk;
}

int runJoints(Context& context, Arguments& arguments) {
  const bool json = jsonOption(arguments, "joints");
  const auto print = [&](const rbsim::joints_t* joints) {
    if (json) {
      printJointsJson(stdout, *context.client.world(), joints);
    } else {
      printJoints(stdout, *context.client.world(), joints);
    }
  };
  // Ask for a fresh description, then the joints' state of its revision.
  context.client.publishWorld();
  if (!context.client.spinUntil([&] { return context.client.world().has_value(); }, context.timeout))
    return noAnswer(context, "world description on " + context.client.channel("WORLD"));
  const rbsim::world_t& world = *context.client.world();
  if (world.total_joints == 0) {
    print(nullptr);
    return kExitOk;
  }
  const auto matching = [&] {
    const auto& joints = context.client.latestJoints();
    return joints && joints->world_revision == context.client.world()->world_revision;
  };
  if (!context.client.spinUntil(matching, context.timeout))
    return noAnswer(context, "joint states on " + context.client.channel("JOINTS"));
  print(&*context.client.latestJoints());
  return kExitOk;
}

client::JointMode parseJointMode(std::string text) {
  if (text == "off") return client::JointMode::Off;
  if (text == "velocity") return client::JointMode::Velocity;
  if (text == "position") return client::JointMode::Position;
  if (text == "effort") return client::JointMode::Effort;
  throw UsageError("joint MODE: expected off, velocity, position or effort, got '" + text + "'");
}

int runJoint(Context& context, Arguments& arguments) {
  client::JointCommand command;
  std::vector<std::string> positional;
  while (!arguments.empty()) {
    const std::string option = arguments.next("joint", "an argument");
    if (option == "--max-effort") {
      command.maxEffort = arguments.nextNumber(option);
    } else if (option == "--stiffness") {
      command.stiffness = arguments.nextNumber(option);
    } else if (option == "--damping") {
      command.damping = arguments.nextNumber(option);
    } else if (option == "--at-step") {
      command.applyAtStep = arguments.nextInteger(option);
    } else if (option.rfind("--", 0) == 0) {
      throw UsageError("joint: unknown option '" + option + "'");
    } else {
      positional.push_back(option);
    }
  }
  if (positional.size() < 2) throw UsageError("joint: missing NAME and MODE");
  if (positional.size() > 3) throw UsageError("joint: unexpected argument '" + positional[3] + "'");
  command.joint = positional[0];
  command.mode = parseJointMode(positional[1]);
  const bool off = command.mode == client::JointMode::Off;
  if (off && positional.size() == 3) throw UsageError("joint: MODE off takes no TARGET");
  if (!off && positional.size() < 3) throw UsageError("joint: MODE " + positional[1] + " needs a TARGET");
  if (!off) command.target = parseNumber(positional[2], "joint TARGET");
  const auto request = context.client.commandJoint(command);
  return report(context, request, "joint " + command.joint + " " + positional[1]);
}

// The spellings of docs/cli.md: hyphens, with underscores accepted too.
client::WrenchMode parseMode(std::string text) {
  std::replace(text.begin(), text.end(), '_', '-');
  if (text == "one-step") return client::WrenchMode::OneStep;
  if (text == "duration") return client::WrenchMode::Duration;
  if (text == "persistent") return client::WrenchMode::Persistent;
  if (text == "clear") return client::WrenchMode::Clear;
  if (text == "clear-all") return client::WrenchMode::ClearAllClients;
  throw UsageError("--mode: expected one-step, duration, persistent, clear or clear-all, got '" +
                   text + "'");
}

client::Frame parseFrame(const std::string& option, const std::string& text) {
  if (text == "world") return client::Frame::World;
  if (text == "body") return client::Frame::Body;
  throw UsageError(option + ": expected world or body, got '" + text + "'");
}

int runWrench(Context& context, Arguments& arguments) {
  client::Wrench wrench;
  bool hasBody = false;
  bool hasMode = false;
  bool hasDuration = false;
  while (!arguments.empty()) {
    const std::string option = arguments.next("wrench", "an option");
    if (option == "--force") {
      wrench.force = arguments.nextVec3(option);
    } else if (option == "--torque") {
      wrench.torque = arguments.nextVec3(option);
    } else if (option == "--point") {
      wrench.point = arguments.nextVec3(option);
    } else if (option == "--frame") {
      wrench.frame = parseFrame(option, arguments.next(option, "world or body"));
    } else if (option == "--point-frame") {
      wrench.pointFrame = parseFrame(option, arguments.next(option, "world or body"));
    } else if (option == "--mode") {
      wrench.mode = parseMode(arguments.next(option, "a mode"));
      hasMode = true;
    } else if (option == "--duration") {
      wrench.duration = arguments.nextNumber(option);
      hasDuration = true;
    } else if (option == "--at-step") {
      wrench.applyAtStep = arguments.nextInteger(option);
    } else if (option.rfind("--", 0) == 0) {
      throw UsageError("wrench: unknown option '" + option + "'");
    } else if (!hasBody) {
      wrench.body = option;
      hasBody = true;
    } else {
      throw UsageError("wrench: unexpected argument '" + option + "'");
    }
  }
  if (hasDuration && !hasMode) wrench.mode = client::WrenchMode::Duration;
  if (wrench.mode == client::WrenchMode::Duration && !hasDuration)
    throw UsageError("wrench: --mode duration needs --duration S");
  const bool clear = wrench.mode == client::WrenchMode::Clear ||
                     wrench.mode == client::WrenchMode::ClearAllClients;
  if (!hasBody && !clear)
    throw UsageError("wrench: missing BODY (only --mode clear or clear-all may leave it out, for "
                     "every body)");
  if (clear && hasDuration)
    throw UsageError("wrench: --duration goes with --mode duration, not " +
                     std::string(wrench.mode == client::WrenchMode::Clear ? "clear" : "clear-all"));

  // With no --point the client library asks the server for the centre of
  // mass (wrench_t::POINT_FRAME_CENTER_OF_MASS), exact whatever the body's shape.
  const auto request = context.client.applyWrench(wrench);
  return report(context, request, "wrench seq " + std::to_string(request.seq));
}

int runSimpleCommand(Context& context, Arguments& arguments, client::Request (Client::*send)(),
                     const std::string& what) {
  arguments.expectEnd();
  return report(context, (context.client.*send)(), what);
}

int runPause(Context& context, Arguments& arguments) {
  return runSimpleCommand(context, arguments, &Client::pause, "pause");
}

int runResume(Context& context, Arguments& arguments) {
  return runSimpleCommand(context, arguments, &Client::resume, "resume");
}

int runReset(Context& context, Arguments& arguments) {
  return runSimpleCommand(context, arguments, &Client::reset, "reset");
}

int runStep(Context& context, Arguments& arguments) {
  int64_t count = 1;
  bool wait = true;
  bool hasCount = false;
  while (!arguments.empty()) {
    const std::string argument = arguments.next("step", "an argument");
    if (argument == "--no-wait") {
      wait = false;
    } else if (!hasCount) {
      count = parseInteger(argument, "step N");
      if (count < 1) throw UsageError("step N: expected N >= 1, got " + argument);
      hasCount = true;
    } else {
      throw UsageError("step: unexpected argument '" + argument + "'");
    }
  }
  std::optional<rbsim::ack_t> ack;
  const int code =
      report(context, context.client.step(count), "step " + std::to_string(count), &ack);
  if (code != kExitOk || !wait) return code;
  // The server publishes the state after the last requested step.
  const int64_t last = ack->effective_step + count - 1;
  const auto reached = [&] {
    const auto& state = context.client.latestState();
    return state && state->step >= last;
  };
  if (!context.client.spinUntil(reached, context.timeout))
    return noAnswer(context, "state of step " + std::to_string(last));
  std::printf("step %lld\n", static_cast<long long>(context.client.latestState()->step));
  return kExitOk;
}

int runRealTimeFactor(Context& context, Arguments& arguments) {
  const double factor = parseNumber(arguments.next("rtf", "a factor X"), "rtf X");
  arguments.expectEnd();
  return report(context, context.client.setRealTimeFactor(factor), "rtf");
}

int runSpawn(Context& context, Arguments& arguments) {
  std::string yaml;
  const std::string source = arguments.next("spawn", "FILE, - or --yaml TEXT");
  if (source == "--yaml") {
    yaml = arguments.next("--yaml", "the body's YAML");
  } else if (source == "-") {
    yaml = readAll(stdin);
  } else {
    std::FILE* file = std::fopen(source.c_str(), "rb");
    if (file == nullptr) throw UsageError("spawn: cannot read '" + source + "'");
    yaml = readAll(file);
    std::fclose(file);
  }
  arguments.expectEnd();
  return report(context, context.client.spawn(yaml), "spawn");
}

int runRemove(Context& context, Arguments& arguments) {
  const std::string name = arguments.next("remove", "a body name or --joint NAME");
  if (name == "--joint") {
    const std::string joint = arguments.next("--joint", "a joint name");
    arguments.expectEnd();
    return report(context, context.client.removeJoint(joint), "remove joint " + joint);
  }
  arguments.expectEnd();
  return report(context, context.client.remove(name), "remove " + name);
}

// --- robot ---------------------------------------------------------------

// Escapes a channel name for LCM's subscription pattern (a POSIX regex).
std::string regexEscaped(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (std::string_view("\\^$.|?*+()[]{}").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

// What a robot verb hears besides its robot (on the Robot's own LCM
// connection, so that the Robot's waits receive it too): the robots whose
// states come on <prefix>ROBOT_STATE, and whether the server was heard at
// all (its world states or statuses, not decoded).
class Hearing {
 public:
  Hearing(lcm::LCM& lcm, const std::string& prefix) : m_channel(prefix + "ROBOT_STATE") {
    lcm.subscribe(regexEscaped(m_channel), &Hearing::onRobotState, this);
    // LCM anchors the pattern at both ends, around the group.
    lcm.subscribe(
        "(" + regexEscaped(prefix + "STATE") + "|" + regexEscaped(prefix + "STATUS") + ")",
        &Hearing::onServer, this);
  }
  const std::string& channel() const { return m_channel; }
  const std::set<std::string>& robots() const { return m_robots; }
  bool server() const { return m_server || !m_robots.empty(); }

 private:
  void onRobotState(const lcm::ReceiveBuffer*, const std::string&,
                    const rbsim::robot_state_t* state) {
    m_robots.insert(state->robot);
  }
  void onServer(const lcm::ReceiveBuffer*, const std::string&) { m_server = true; }

  std::string m_channel;
  std::set<std::string> m_robots;
  bool m_server = false;
};

// Handles the Robot's messages until `done()` or `timeout`; returns done().
bool spinRobot(client::Robot& robot, const std::function<bool()>& done, Client::Timeout timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    const auto left =
        std::chrono::ceil<Client::Timeout>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0 || robot.handle(std::min(left, Client::Timeout(50))) < 0) return done();
  }
  return true;
}

// Says why no (suitable) state of `robot` came within `timeout` and returns
// the exit status: rejected (1) when the server was heard, naming the robots
// it publishes; no answer (3) when nothing was, or states of the robot came
// but not the one waited for.
int robotMissing(Context& context, const Hearing& hearing, const client::Robot& robot,
                 Client::Timeout timeout, uint64_t after = 0) {
  const double seconds = static_cast<double>(timeout.count()) * 1e-3;
  const char* name = robot.name().c_str();
  if (robot.stateCount() > after) {
    std::fprintf(stderr, "rbctl: no state of robot '%s' as expected on %s within %.3g s\n", name,
                 hearing.channel().c_str(), seconds);
    return kExitNoAnswer;
  }
  if (!hearing.robots().empty()) {
    const std::vector<std::string> heard(hearing.robots().begin(), hearing.robots().end());
    std::string list;
    for (const std::string& other : heard) list += (list.empty() ? "" : ", ") + other;
    std::fprintf(stderr, "rbctl: no robot named '%s' on %s within %.3g s%s; robots heard: %s\n",
                 name, hearing.channel().c_str(), seconds, didYouMean(robot.name(), heard).c_str(),
                 list.c_str());
    return kExitRejected;
  }
  if (hearing.server()) {
    std::fprintf(stderr,
                 "rbctl: no robot named '%s': no robot states on %s within %.3g s (robots heard: "
                 "none)\n",
                 name, hearing.channel().c_str(), seconds);
    return kExitRejected;
  }
  return noAnswer(context, "robot state on " + hearing.channel());
}

int runRobotState(Context& context, Arguments& arguments) {
  std::string name;
  bool json = false;
  bool dynamics = false;
  while (!arguments.empty()) {
    const std::string argument = arguments.next("robot state", "an argument");
    if (argument == "--json") {
      json = true;
    } else if (argument == "--dynamics") {
      dynamics = true;
    } else if (argument.rfind("--", 0) == 0) {
      throw UsageError("robot state: unknown option '" + argument + "'");
    } else if (name.empty()) {
      name = argument;
    } else {
      throw UsageError("robot state: unexpected argument '" + argument + "'");
    }
  }
  if (name.empty()) throw UsageError("robot state: missing NAME");
  client::Robot robot(name, context.options);
  Hearing hearing(robot.lcm(), context.client.channelPrefix());
  if (dynamics) {
    robot.setDynamics(true);
    const auto ack = robot.waitForAck(robot.send(), context.timeout);
    if (!ack) return noAnswer(context, "acknowledgement of the robot command");
    if (!ack->accepted) {
      std::fprintf(stderr, "rbctl: robot %s dynamics rejected: %s\n", name.c_str(),
                   ack->reason.c_str());
      return kExitRejected;
    }
  }
  // With --dynamics a state that carries them (or says why it cannot): the
  // Robot holds only states that came since it was made, before the request.
  if (!robot.waitForState(context.timeout, dynamics))
    return robotMissing(context, hearing, robot, context.timeout);
  if (json) {
    printRobotStateJson(stdout, *robot.state(), dynamics);
  } else {
    printRobotState(stdout, *robot.state(), dynamics);
  }
  return kExitOk;
}

// A comma list's items, none empty.
std::vector<std::string> commaList(const std::string& option, const std::string& text,
                                   const std::string& what) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    items.push_back(
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (items.back().empty())
      throw UsageError(option + ": expected " + what + " separated by commas, got '" + text + "'");
    if (comma == std::string::npos) return items;
    start = comma + 1;
  }
}

// `values` for `count` joints: one value for all, or one each.
template <class T>
std::vector<T> perJoint(const std::string& option, const std::vector<T>& values,
                        std::size_t count) {
  if (values.size() == 1) return std::vector<T>(count, values.front());
  if (values.size() != count)
    throw UsageError(option + ": " + std::to_string(values.size()) + " values for " +
                     std::to_string(count) + " joints (give one for all, or one per joint)");
  return values;
}

int8_t parseRobotMode(const std::string& text) {
  if (text == "keep") return rbsim::robot_command_t::MODE_KEEP;
  if (text == "off") return rbsim::robot_command_t::MODE_OFF;
  if (text == "velocity") return rbsim::robot_command_t::MODE_VELOCITY;
  if (text == "position") return rbsim::robot_command_t::MODE_POSITION;
  if (text == "effort") return rbsim::robot_command_t::MODE_EFFORT;
  throw UsageError("--mode: expected keep, off, velocity, position or effort, got '" + text + "'");
}

// robot_command_t's per-joint numbers, by option.
const std::pair<const char*, std::vector<double> rbsim::robot_command_t::*> kRobotValues[] = {
    {"--position", &rbsim::robot_command_t::position},
    {"--velocity", &rbsim::robot_command_t::velocity},
    {"--effort", &rbsim::robot_command_t::effort},
    {"--stiffness", &rbsim::robot_command_t::stiffness},
    {"--damping", &rbsim::robot_command_t::damping},
    {"--max-effort", &rbsim::robot_command_t::max_effort}};

int runRobotCommand(Context& context, Arguments& arguments) {
  std::string name;
  std::vector<std::string> joints;
  std::optional<std::string> modeText;
  std::map<std::string, std::string> valueTexts;  // option -> its comma list
  int64_t atStep = -1;
  double stateRate = 0.0;
  int64_t steps = 0;
  while (!arguments.empty()) {
    const std::string argument = arguments.next("robot command", "an argument");
    const auto isValue = [&](const auto& entry) { return argument == entry.first; };
    if (argument == "--joint") {
      joints.push_back(arguments.next(argument, "joint names"));
    } else if (argument == "--mode") {
      modeText = arguments.next(argument, "modes");
    } else if (std::any_of(std::begin(kRobotValues), std::end(kRobotValues), isValue)) {
      valueTexts[argument] = arguments.next(argument, "numbers");
    } else if (argument == "--at-step") {
      atStep = arguments.nextInteger(argument);
    } else if (argument == "--state-rate") {
      stateRate = arguments.nextNumber(argument);
    } else if (argument == "--steps") {
      steps = arguments.nextInteger(argument);
    } else if (argument.rfind("--", 0) == 0) {
      throw UsageError("robot command: unknown option '" + argument + "'");
    } else if (name.empty()) {
      name = argument;
    } else {
      throw UsageError("robot command: unexpected argument '" + argument + "'");
    }
  }
  if (name.empty()) throw UsageError("robot command: missing NAME");
  // Everything that does not depend on the robot is checked first, as the
  // Python CLI does.
  std::vector<std::string> names;
  for (const std::string& text : joints)
    for (std::string& joint : commaList("--joint", text, "joint names")) names.push_back(joint);
  std::vector<std::string> modes;
  if (modeText)
    for (std::string& mode : commaList("--mode", *modeText, "modes")) {
      parseRobotMode(mode);
      modes.push_back(mode);
    }
  std::map<std::string, std::vector<double>> values;
  for (const auto& [option, text] : valueTexts)
    for (const std::string& item : commaList(option, text, "numbers"))
      values[option].push_back(parseNumber(item, option));
  if ((!names.empty() || !values.empty()) && !modeText)
    throw UsageError("give --mode for the joints commanded");
  for (const std::string& mode : modes)
    if ((mode == "velocity" || mode == "position" || mode == "effort") &&
        values.count("--" + mode) == 0)
      throw UsageError("--mode " + mode + " needs --" + mode);
  if (steps < 0) throw UsageError("--steps: expected N >= 0, got " + std::to_string(steps));
  if (steps > INT32_MAX) throw UsageError("--steps: at most " + std::to_string(INT32_MAX));

  client::Robot robot(name, context.options);
  Hearing hearing(robot.lcm(), context.client.channelPrefix());
  if (modeText) {
    std::size_t count = names.size();
    if (names.empty()) {
      // No --joint: every joint of the robot, in its order, so its count.
      if (!robot.waitForState(context.timeout))
        return robotMissing(context, hearing, robot, context.timeout);
      count = static_cast<std::size_t>(robot.numJoints());
    }
    rbsim::robot_command_t entries{};
    for (const std::string& mode : perJoint("--mode", modes, count))
      entries.mode.push_back(parseRobotMode(mode));
    for (const auto& [option, field] : kRobotValues) {
      const auto given = values.find(option);
      entries.*field = given == values.end() ? std::vector<double>(count, 0.0)
                                             : perJoint(option, given->second, count);
    }
    entries.num_joints = static_cast<int32_t>(count);
    entries.joint_names = names;
    entries.num_names = static_cast<int32_t>(names.size());
    robot.commandRaw(entries);
  }
  robot.setStateRate(stateRate);
  const uint64_t before = robot.stateCount();
  const auto ack =
      robot.waitForAck(robot.send(atStep, static_cast<int32_t>(steps)), context.timeout);
  if (!ack) return noAnswer(context, "acknowledgement of the robot command");
  const std::string what = "robot " + name + " command";
  if (!ack->accepted) {
    std::fprintf(stderr, "rbctl: %s rejected: %s\n", what.c_str(), ack->reason.c_str());
    return kExitRejected;
  }
  std::printf("%s accepted: effective_step %lld", what.c_str(),
              static_cast<long long>(ack->effective_step));
  if (!ack->reason.empty()) std::printf(" note %s", ack->reason.c_str());
  std::printf("\n");
  if (steps == 0) return kExitOk;
  // The server publishes the robot's state after the last step.
  const int64_t last = ack->effective_step + steps - 1;
  const Client::Timeout wait = context.timeout + Client::Timeout(steps);
  if (!spinRobot(
          robot, [&] { return robot.stateCount() > before && robot.state()->step >= last; }, wait))
    return robotMissing(context, hearing, robot, wait, before);
  std::printf("step %lld\n", static_cast<long long>(robot.state()->step));
  return kExitOk;
}

int runRobot(Context& context, Arguments& arguments) {
  if (arguments.empty()) throw UsageError("missing state or command");
  const std::string verb = arguments.next("robot", "state or command");
  if (verb == "state") return runRobotState(context, arguments);
  if (verb == "command") return runRobotCommand(context, arguments);
  throw UsageError("expected state or command, got '" + verb + "'");
}

}  // namespace

const std::vector<Verb>& verbs() {
  static const std::vector<Verb> kVerbs = {
      {"state", "print the latest complete state",
       "usage: rbctl state [--body NAME]... [--json]\n\n"
       "Waits for a complete state on <prefix>STATE and prints it: a line\n"
       "\"step S sim_time T world_revision R bodies N\", then per body \"body NAME id I\n"
       "position X Y Z orientation W X Y Z linear_velocity ... angular_velocity ...\"\n"
       "(m, unit quaternion body->world, m/s and rad/s in the world frame).\n"
       "(orientation components below 1e-12 are printed as 0).\n"
       "  --body NAME   only that body (repeatable; exit 1 if there is none)\n"
       "  --json        one JSON object: step, sim_time, world_revision, bodies\n",
       runState},
      {"status", "print the latest heartbeat",
       "usage: rbctl status [--json]\n\nWaits for a heartbeat on <prefix>STATUS and prints its "
       "fields\n"
       "(--json: as one JSON object).\n",
       runStatus},
      {"bodies", "print the world description (bodies, shapes, masses)",
       "usage: rbctl bodies [--json]\n\n"
       "Asks the server to publish the world description (PUBLISH_WORLD) and prints\n"
       "the world settings and every body's id, shape, mass (kg) and principal\n"
       "moments of inertia (kg m^2).\n",
       runBodies},
      {"wrench", "apply a force and torque to a body",
       "usage: rbctl wrench BODY [--force FX FY FZ] [--torque TX TY TZ] [--point X Y Z]\n"
       "                    [--frame world|body] [--point-frame world|body]\n"
       "                    [--mode one-step|duration|persistent|clear|clear-all]\n"
       "                    [--duration S] [--at-step K]\n"
       "       rbctl wrench [BODY] --mode clear|clear-all   (no BODY: every body)\n\n"
       "  --force       N, in --frame (default 0 0 0)\n"
       "  --torque      N m, in --frame: a pure couple (default 0 0 0)\n"
       "  --frame       of force and torque: world (default; keeps its world direction)\n"
       "                or body (turns with the body)\n"
       "  --point       m, in --point-frame: where the force acts, a point of the body.\n"
       "                Default: the centre of mass, exactly (placed by the server)\n"
       "  --point-frame world (a world position when the wrench first acts, carried\n"
       "                with the body from then on) or body (fixed in the body).\n"
       "                Default: the same as --frame\n"
       "  --mode        one-step (default), duration, persistent, clear (this client's\n"
       "                duration and persistent wrenches) or clear-all (every client's);\n"
       "                a clear's ack says how many it cleared\n"
       "  --duration    s of simulated time (implies --mode duration)\n"
       "  --at-step K   the step during which it first acts (default: the next)\n"
       "The body frame is the frame the body is given in (its config frame).\n\n"
       "Note: clear and persistent replacement work per client id, and every rbctl run\n"
       "is a new client unless --client-id (or $RBSIM_CLIENT_ID) names one: to clear a\n"
       "persistent wrench later,\n"
       "  rbctl --client-id me wrench bouncy_ball --force 0 0 5 --mode persistent\n"
       "  rbctl --client-id me wrench bouncy_ball --mode clear\n"
       "or clear whoever's it is with --mode clear-all.\n",
       runWrench},
      {"pause", "stop stepping", "usage: rbctl pause\n\nSends PAUSE and waits for its ack.\n",
       runPause},
      {"resume", "step again at the target real-time factor",
       "usage: rbctl resume\n\nSends RESUME and waits for its ack.\n", runResume},
      {"step", "take N steps while paused",
       "usage: rbctl step [N] [--no-wait]\n\n"
       "Sends STEP N (default 1; the server must be paused), waits for its ack and,\n"
       "unless --no-wait, for the state after the last of the steps.\n",
       runStep},
      {"reset", "go back to the initial world, step 0",
       "usage: rbctl reset\n\nSends RESET and waits for its ack.\n", runReset},
      {"rtf", "set the real-time factor",
       "usage: rbctl rtf X\n\nSimulated s per wall-clock s: X > 0 paces the simulation,\n"
       "0 runs it as fast as possible.\n",
       runRealTimeFactor},
      {"spawn", "add bodies and joints",
       "usage: rbctl spawn FILE | - | --yaml TEXT\n\n"
       "Sends SPAWN with one body in the YAML schema of a `bodies:` entry of the\n"
       "config file, or a mapping with `bodies:` and `joints:` lists as a world\n"
       "file has them (joints may join the world's bodies; all are added or none),\n"
       "read from FILE, from standard input (-) or given inline, e.g.\n"
       "  rbctl spawn --yaml '{name: probe, shape: {type: sphere, radius: 0.1}, mass: 1,\n"
       "                      position: [0, 0, 2]}'\n",
       runSpawn},
      {"remove", "remove a body (with its joints) or a joint",
       "usage: rbctl remove NAME | --joint NAME\n\n"
       "Sends REMOVE for the body NAME (its joints go with it) or the joint NAME\n"
       "and waits for its ack.\n",
       runRemove},
      {"joints", "print the joints (type, bodies, axis, limits) and their state",
       "usage: rbctl joints [--json]\n\n"
       "Asks the server to publish the world description (PUBLISH_WORLD) and prints a\n"
       "line \"joints N step S world_revision R\", then per joint \"joint NAME type T\n"
       "body_a A body_b B axis X Y Z limits LOWER UPPER|none [length L] [spring]\n"
       "[cone C] position P rate V effort E at_limit L active true|false\" (the world\n"
       "is \"world\"; axis in the world frame; rad, rad/s and N m for revolute joints,\n"
       "m, m/s and N for prismatic and distance ones).\n"
       "  --json   one JSON object: step, world_revision, joints (each with its\n"
       "           description and state fields)\n",
       runJoints},
      {"sensor", "print a sensor's readings",
       "usage: rbctl sensor NAME [--count N]\n\n"
       "Waits for readings of the sensor NAME (the world file's sensors:) on\n"
       "<prefix>SENSOR_NAME and prints each as one line \"sensor NAME type T step S\n"
       "sim_time T\" and its fields: imu: body, linear_acceleration (m/s^2, specific\n"
       "force), angular_velocity (rad/s), both in the sensor frame, orientation (w x y\n"
       "z, sensor to world); contact: body, force (N), torque (N m), contacts;\n"
       "force_torque: joint, body, force, torque; range_scan: body, position,\n"
       "orientation, beams, samples, returns, nearest and farthest return (m; inf:\n"
       "none), and with at most 16 beams the ranges (inf: no return, -inf: below the\n"
       "minimum range) and hit_bodies (- for none) when the sensor reports them.\n"
       "  --count N   print N readings (default 1)\n",
       runSensor},
      {"joint", "command a joint's motor, position drive or effort",
       "usage: rbctl joint NAME off|velocity|position|effort [TARGET] [--max-effort E]\n"
       "                   [--stiffness K] [--damping D] [--at-step K]\n\n"
       "The modes are exclusive: each turns the joint's other actuators off.\n"
       "  off           motor, drive and effort off (no TARGET)\n"
       "  velocity      the motor drives the rate to TARGET (rad/s or m/s) with at most\n"
       "                --max-effort E (N m or N; default 0: the joint's effort\n"
       "                limit, refused for a joint without one)\n"
       "  position      a spring --stiffness K (N m/rad or N/m) and damper --damping D\n"
       "                (N m s/rad or N s/m) pull the joint to TARGET (rad or m);\n"
       "                --max-effort E caps the effort (default 0: uncapped); a\n"
       "                distance spring: TARGET is its rest length (m)\n"
       "  effort        a constant TARGET (N m or N) along the axis\n"
       "  --at-step K   the step from which it acts (default: the next)\n",
       runJoint},
      {"robot", "a robot's state, or one command for all its joints",
       "usage: rbctl robot state NAME [--json] [--dynamics]\n"
       "       rbctl robot command NAME [--joint J[,J...]]... [--mode M[,M...]]\n"
       "                     [--position Q,...] [--velocity V,...] [--effort E,...]\n"
       "                     [--stiffness K,...] [--damping D,...] [--max-effort E,...]\n"
       "                     [--at-step K] [--state-rate HZ] [--steps N]\n\n"
       "A robot is the joints named NAME/... . robot state waits for its next\n"
       "robot_state_t and prints \"robot NAME step S sim_time T world_revision R\n"
       "joints N\", per joint \"joint NAME position P velocity V effort E [leader L]\"\n"
       "(rad or m, rad/s or m/s, N m or N; a mimic follower names its leader) and\n"
       "\"base NAME fixed B position ... orientation ... linear_velocity ...\n"
       "angular_velocity ...\" (world frame). Exit 1 when no state of NAME comes\n"
       "within --timeout (it lists the robots heard).\n"
       "  --json        one JSON object with the wire field names\n"
       "  --dynamics    turn the robot's dynamics on first (they stay on) and print\n"
       "                them too: \"dynamics dofs N links L [note TEXT]\", the rows\n"
       "                \"mass_matrix I ...\" of M, \"bias ...\" (h), \"gravity ...\" (g)\n"
       "                and \"link NAME position ... orientation ...\" (--json: and\n"
       "                each link's Jacobian)\n\n"
       "robot command sends one robot_command_t, applied whole at one step or refused\n"
       "whole (exit 1, the server's reason naming the joint), and prints\n"
       "\"robot NAME command accepted: effective_step K\". Values are comma lists,\n"
       "one per joint commanded; a single value is for every joint.\n"
       "  --joint J     the joints commanded, J or NAME/J (repeatable, or a comma\n"
       "                list; default: every joint of the robot, in its order)\n"
       "  --mode M      keep (left as it is: a mimic follower's), off, velocity,\n"
       "                position or effort; needed to command joints\n"
       "  --position    rad or m: position's target (needed by position)\n"
       "  --velocity    rad/s or m/s: velocity's target (needed by velocity);\n"
       "                position: the rate the damping pulls to (default 0)\n"
       "  --effort      N m or N: effort's (needed by effort); position and velocity:\n"
       "                a feed-forward effort added (default 0)\n"
       "  --stiffness   position: N m/rad or N/m (default 0; not both 0 with --damping)\n"
       "  --damping     position: N m s/rad or N s/m (default 0)\n"
       "  --max-effort  N m or N: velocity: the motor's largest effort (default 0: the\n"
       "                joint's effort limit); position: the drive's cap (default 0:\n"
       "                uncapped)\n"
       "  --at-step K   the step from which it acts (default: the next)\n"
       "  --state-rate HZ  how often the server publishes the robot's state from now\n"
       "                on (default 0: as it is; -1: with every world state)\n"
       "  --steps N     while paused: take N steps after applying it, then wait for\n"
       "                the robot's state after the last and print \"step S\"\n"
       "Without --mode, no joint changes: e.g. only --steps or --state-rate.\n",
       runRobot},
  };
  return kVerbs;
}

}  // namespace rbsim::rbctl
