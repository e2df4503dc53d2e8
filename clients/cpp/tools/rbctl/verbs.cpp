#include "verbs.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <rbsim/wrench_t.hpp>

#include "printing.h"
#include "rbsim/client/lookup.h"

namespace rbsim::rbctl {

namespace {

using client::Client;

double seconds(Client::Timeout timeout) {
  return static_cast<double>(timeout.count()) * 1e-3;
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
      std::fprintf(stderr, "rbctl: no body named '%s' in the state of step %lld\n", body.c_str(),
                   static_cast<long long>(state.step));
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
       "usage: rbctl status [--json]\n\nWaits for a heartbeat on <prefix>STATUS and prints its fields\n"
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
  };
  return kVerbs;
}

}  // namespace rbsim::rbctl
