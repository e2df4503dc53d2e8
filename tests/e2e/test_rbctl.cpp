// rbctl, the command-line client, run as a separate process against a server
// while the test's own client watches what the server does.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

#include "e2e_paths.h"
#include "rbsim/client/lookup.h"
#include "rigid_body_math.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

class Rbctl : public ServerTest {
 protected:
  ProcessResult rbctl(std::vector<std::string> arguments) {
    std::vector<std::string> argv = {kRbctl, "--url", kUrl, "--timeout", "5"};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    return runProcess(argv, scratchPath("rbctl.log"), 30s);
  }
  // rbctl without the global options (for usage errors and --help).
  ProcessResult rbctlBare(std::vector<std::string> arguments) {
    arguments.insert(arguments.begin(), kRbctl);
    return runProcess(arguments, scratchPath("rbctl.log"), 30s);
  }

  static int64_t integerAfter(const std::string& text, const std::string& key) {
    std::smatch match;
    if (!std::regex_search(text, match, std::regex("(^|\\s)" + key + " (-?[0-9]+)")))
      throw std::runtime_error("no '" + key + " N' in:\n" + text);
    return std::stoll(match[2]);
  }
  static Vec3 vectorAfter(const std::string& text, const std::string& key) {
    const auto at = text.find(" " + key + " ");
    if (at == std::string::npos) throw std::runtime_error("no '" + key + "' in:\n" + text);
    std::istringstream in(text.substr(at + key.size() + 2));
    Vec3 v{};
    in >> v[0] >> v[1] >> v[2];
    return v;
  }
};

void expectExitStatus(const ProcessResult& run, int expected) {
  ASSERT_TRUE(run.status.has_value()) << "did not end:\n" << run.output;
  EXPECT_EQ(*run.status, expected) << run.output;
}

TEST_F(Rbctl, PauseStepStateAndWrench) {
  startServer("free_bodies.yaml", {"--state-rate", "0"});
  waitFor("the server to step", [&] { return currentStep() >= 10; });

  const ProcessResult pause = rbctl({"pause"});
  expectExitStatus(pause, 0);
  const int64_t pausedAt = integerAfter(pause.output, "effective_step") - 1;
  client().spinUntil([] { return false; }, 100ms);
  EXPECT_EQ(currentStep(), pausedAt) << "rbctl pause paused the server";

  const ProcessResult step = rbctl({"step", "5"});
  expectExitStatus(step, 0);
  EXPECT_EQ(integerAfter(step.output, "effective_step"), pausedAt + 1);
  waitForStep(pausedAt + 5);

  const ProcessResult state = rbctl({"state"});
  expectExitStatus(state, 0);
  EXPECT_EQ(integerAfter(state.output, "step"), pausedAt + 5) << state.output;
  EXPECT_NE(state.output.find("body puck id"), std::string::npos) << state.output;
  EXPECT_NE(state.output.find("body ball id"), std::string::npos) << state.output;

  // A one-step push through the centre of mass (rbctl's default point).
  const ProcessResult wrench = rbctl({"wrench", "puck", "--force", "3", "0", "0"});
  expectExitStatus(wrench, 0);
  EXPECT_EQ(integerAfter(wrench.output, "effective_step"), pausedAt + 6);
  expectExitStatus(rbctl({"step"}), 0);  // N defaults to 1
  const ProcessResult puck = rbctl({"state", "--body", "puck"});
  expectExitStatus(puck, 0);
  EXPECT_EQ(puck.output.find("body ball"), std::string::npos) << "--body prints only that body";
  const double dt = client().world()->dt;
  const double mass = description("puck").mass;
  const Vec3 expected{0.2 + 3.0 * dt / mass, -0.1, 0.05};
  EXPECT_LT(relativeError(vectorAfter(puck.output, "linear_velocity"), expected), 1e-8)
      << puck.output;
  waitForStep(pausedAt + 6);
  EXPECT_LT(relativeError(toVec3(history().body(pausedAt + 6, "puck").linear_velocity), expected),
            1e-12);

  // A world force at a body corner (--point-frame body) turns the box at
  // rest by the moment of the force about its centre, (R r) × F: the flag
  // reached the server (read as a world point the same numbers give another
  // moment, see test_wrench_physics.cpp).
  const int64_t beforeCorner = currentStep();
  const auto& tiltedBefore = history().body(beforeCorner, "tilted");
  expectExitStatus(rbctl({"wrench", "tilted", "--force", "0", "0", "1e-6", "--point", "0.2", "0.1",
                          "0.05", "--point-frame", "body"}),
                   0);
  expectExitStatus(rbctl({"step"}), 0);
  waitForStep(beforeCorner + 1);
  const auto& tiltedAfter = history().body(beforeCorner + 1, "tilted");
  const Vec3 change = angularMomentum(tiltedAfter.orientation, description("tilted").inertia,
                                      tiltedAfter.angular_velocity) -
                      angularMomentum(tiltedBefore.orientation, description("tilted").inertia,
                                      tiltedBefore.angular_velocity);
  const Vec3 moment =
      cross(rotationOf(tiltedBefore.orientation) * Vec3{0.2, 0.1, 0.05}, Vec3{0.0, 0.0, 1e-6});
  EXPECT_LT(relativeError(change, dt * moment), 1e-9);

  // Duration, body frame, scheduled: accepted with the requested step.
  const ProcessResult scheduled =
      rbctl({"wrench", "tilted", "--frame", "body", "--force", "0", "1", "0", "--duration", "0.01",
             "--at-step", std::to_string(pausedAt + 20)});
  expectExitStatus(scheduled, 0);
  EXPECT_EQ(integerAfter(scheduled.output, "effective_step"), pausedAt + 20);
}

TEST_F(Rbctl, OtherVerbs) {
  startServer("free_bodies.yaml", {"--paused"});

  const ProcessResult status = rbctl({"status"});
  expectExitStatus(status, 0);
  EXPECT_NE(status.output.find("paused true"), std::string::npos) << status.output;
  EXPECT_EQ(integerAfter(status.output, "num_bodies"), 4);

  const ProcessResult bodies = rbctl({"bodies"});
  expectExitStatus(bodies, 0);
  EXPECT_NE(bodies.output.find("body puck id 1 shape box static false mass 1.5"), std::string::npos)
      << bodies.output;
  EXPECT_NE(bodies.output.find("body ball id 4 shape sphere"), std::string::npos) << bodies.output;

  const ProcessResult spawn =
      rbctl({"spawn", "--yaml",
             "{name: probe, shape: {type: sphere, radius: 0.1}, mass: 1, position: [0, 0, 5]}"});
  expectExitStatus(spawn, 0);
  waitFor("the probe", [&] { return client::findBody(*client().world(), "probe") != nullptr; });

  const std::string file = scratchPath("body.yaml");
  std::ofstream(file)
      << "name: cube\nshape: {type: box, half_extents: [0.1, 0.1, 0.1]}\nposition: [3, 3, 3]\n";
  expectExitStatus(rbctl({"spawn", file}), 0);
  waitFor("the cube", [&] { return client::findBody(*client().world(), "cube") != nullptr; });

  expectExitStatus(rbctl({"remove", "probe"}), 0);
  waitFor("the probe to go",
          [&] { return client::findBody(*client().world(), "probe") == nullptr; });

  expectExitStatus(rbctl({"rtf", "3"}), 0);
  expectExitStatus(rbctl({"resume"}), 0);
  waitFor("steps after rbctl resume", [&] { return currentStep() >= 30; });
  expectExitStatus(rbctl({"pause"}), 0);

  expectExitStatus(rbctl({"reset"}), 0);
  waitFor("step 0 after rbctl reset", [&] {
    return currentStep() == 0 && client::findBody(*client().latestState(), "cube") == nullptr;
  });

  // A persistent push set by one rbctl run and cleared by another under the same id.
  const double dt = client().world()->dt;
  const double mass = description("ball").mass;
  expectExitStatus(rbctl({"--client-id", "e2e-rbctl", "wrench", "ball", "--force", "0", "0", "2",
                          "--mode", "persistent"}),
                   0);
  expectExitStatus(rbctl({"step", "2"}), 0);
  expectExitStatus(rbctl({"--client-id", "e2e-rbctl", "wrench", "--mode", "clear"}), 0);
  const ProcessResult stepped = rbctl({"step", "3"});
  expectExitStatus(stepped, 0);
  const int64_t last = integerAfter(stepped.output, "effective_step") + 2;
  waitForStep(last);
  EXPECT_NEAR(history().body(last, "ball").linear_velocity[2], 2.0 * 2.0 * dt / mass, 1e-12)
      << "two steps of 2 N, then cleared";
}

TEST_F(Rbctl, RejectionsTimeoutsAndBadArguments) {
  startServer("free_bodies.yaml", {});  // running

  // Rejected by the server: exit 1 with the server's reason.
  const ProcessResult unknown = rbctl({"wrench", "no_such_body", "--force", "1", "0", "0"});
  expectExitStatus(unknown, 1);
  EXPECT_NE(unknown.output.find("unknown body 'no_such_body'"), std::string::npos)
      << unknown.output;
  const ProcessResult running = rbctl({"step", "3"});
  expectExitStatus(running, 1);
  EXPECT_NE(running.output.find("paused"), std::string::npos) << running.output;
  expectExitStatus(rbctl({"state", "--body", "no_such_body"}), 1);

  // Nobody answers on another prefix: exit 3, and it says what it waited for.
  const ProcessResult silent = rbctl({"--prefix", "NOBODY_", "--timeout", "0.3", "pause"});
  expectExitStatus(silent, 3);
  EXPECT_NE(silent.output.find("no acknowledgement"), std::string::npos) << silent.output;
  expectExitStatus(rbctl({"--prefix", "NOBODY_", "--timeout", "0.3", "state"}), 3);

  // Bad arguments: exit 2 with the offending argument named.
  for (const auto& arguments : std::vector<std::vector<std::string>>{
           {"step", "abc"},
           {"step", "0"},
           {"frobnicate"},
           {"wrench", "puck", "--frame", "sideways"},
           {"wrench", "puck", "--point-frame", "up"},
           {"wrench", "puck", "--force", "1", "nan", "0"},
           {"wrench", "puck", "--mode", "duration"},
           {"wrench", "--force", "1", "0", "0"},
           {"rtf"},
           {"remove"},
           {"pause", "now"},
           {"--timeout"},
           {"robot"},
           {"robot", "state"},
           {"robot", "command", "puck", "--joint", "a", "--effort", "1"},
           {"robot", "command", "puck", "--joint", "a,b", "--mode", "effort", "--effort", "1,2,3"},
           {"robot", "command", "puck", "--steps", "-2"},
       }) {
    const ProcessResult bad = rbctl(arguments);
    expectExitStatus(bad, 2);
    EXPECT_NE(bad.output.find("rbctl"), std::string::npos) << bad.output;
  }
  // No LCM at all: exit 4.
  expectExitStatus(rbctlBare({"--url", "nosuch://x", "status"}), 4);

  // Help: the verb list, and each verb's usage.
  const ProcessResult help = rbctlBare({"--help"});
  expectExitStatus(help, 0);
  for (const char* verb : {"state", "status", "bodies", "wrench", "pause", "resume", "step",
                           "reset", "spawn", "remove", "joints", "joint", "robot"}) {
    EXPECT_NE(help.output.find(std::string("  ") + verb + " "), std::string::npos) << verb;
    const ProcessResult usage = rbctlBare({verb, "--help"});
    expectExitStatus(usage, 0);
    EXPECT_NE(usage.output.find(std::string("usage: rbctl ") + verb), std::string::npos)
        << usage.output;
  }
  expectExitStatus(rbctlBare({}), 2);

  // None of it disturbed the server.
  const int64_t now = currentStep();
  waitFor("the server to keep stepping", [&] { return currentStep() >= now + 30; });
}

// rbctl's robot verb on the seven-joint arm (config/worlds/robot_arm.yaml:
// robot "arm", each joint held by a servo), checked against what the
// server publishes on JOINTS and against the servo's statics.
TEST_F(Rbctl, RobotStateAndCommand) {
  startServer(std::string(kConfigWorldsDir) + "/robot_arm.yaml", {"--paused", "--state-rate", "0"});

  // The state: the seven joints in order, as the JOINTS channel has them.
  const ProcessResult state = rbctl({"robot", "state", "arm"});
  expectExitStatus(state, 0);
  const int64_t step = integerAfter(state.output, "step");
  waitFor("the joints of the state's step",
          [&] { return client().latestJoints() && client().latestJoints()->step >= step; });
  const std::regex jointLine("joint (\\S+) position (\\S+) velocity \\S+ effort \\S+");
  std::vector<std::string> names;
  std::istringstream lines(state.output);
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (!std::regex_match(line, match, jointLine)) continue;
    names.push_back(match[1]);
    const rbsim::joint_state_t* published = client().jointState(match[1]);
    ASSERT_NE(published, nullptr) << line;
    char expected[64];
    std::snprintf(expected, sizeof expected, "%.10g", published->position);
    EXPECT_EQ(match[2].str(), expected) << line;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"arm/joint1", "arm/joint2", "arm/joint3", "arm/joint4",
                                             "arm/joint5", "arm/joint6", "arm/joint7"}))
      << state.output;
  EXPECT_NE(
      state.output.find("\nbase arm/base_link fixed true position 0 0 0 orientation 1 0 0 0 "),
      std::string::npos)
      << state.output;

  // Refused whole, naming the joint and the closest names; an unknown robot
  // named with the robots heard.
  const ProcessResult unknownJoint =
      rbctl({"robot", "command", "arm", "--joint", "joint9", "--mode", "off"});
  expectExitStatus(unknownJoint, 1);
  EXPECT_NE(unknownJoint.output.find("joint9"), std::string::npos) << unknownJoint.output;
  EXPECT_NE(unknownJoint.output.find("did you mean"), std::string::npos) << unknownJoint.output;
  const ProcessResult unknownRobot = rbctl({"robot", "state", "ram", "--timeout", "0.5"});
  expectExitStatus(unknownRobot, 1);
  EXPECT_NE(unknownRobot.output.find("(did you mean 'arm'?); robots heard: arm"), std::string::npos)
      << unknownRobot.output;

  // A position command on joint 1 (about the vertical: gravity does not
  // load it) with a second of steps: the servo settles within hundredths of
  // a second, after which only the joint's dry friction (arm7.urdf: 0.3 N m)
  // holds it off the target, by at most friction / stiffness.
  const int64_t before = currentStep();
  const double target = client().jointState("arm/joint1")->position + 0.2;
  const double stiffness = 2000.0;
  char targetText[32];
  std::snprintf(targetText, sizeof targetText, "%.17g", target);
  const ProcessResult command =
      rbctl({"robot", "command", "arm", "--joint", "joint1", "--mode", "position", "--position",
             targetText, "--stiffness", "2000", "--damping", "100", "--steps", "1000"});
  expectExitStatus(command, 0);
  EXPECT_EQ(integerAfter(command.output, "effective_step"), before + 1) << command.output;
  EXPECT_NE(command.output.find("\nstep " + std::to_string(before + 1000) + "\n"),
            std::string::npos)
      << command.output;
  waitForStep(before + 1000);
  waitFor("the joints after the steps",
          [&] { return client().latestJoints()->step == before + 1000; });
  EXPECT_LE(std::abs(client().jointState("arm/joint1")->position - target), 0.3 / stiffness);
  // Exactly N steps: paused after them.
  spinFor(300ms);
  EXPECT_EQ(currentStep(), before + 1000);

  // --steps is for a paused server.
  expectExitStatus(rbctl({"resume"}), 0);
  const ProcessResult running = rbctl({"robot", "command", "arm", "--steps", "1"});
  expectExitStatus(running, 1);
  EXPECT_NE(running.output.find("robot arm command rejected: "), std::string::npos)
      << running.output;
}

// A mimic follower (config/worlds/panda.yaml: the second finger follows the
// first) takes no command of its own: refused naming it; given keep,
// beside its leader's target, accepted.
TEST_F(Rbctl, RobotFollowerTakesOnlyKeep) {
  startServer(std::string(kConfigWorldsDir) + "/panda.yaml", {"--paused"});
  const ProcessResult state = rbctl({"robot", "state", "panda"});
  expectExitStatus(state, 0);
  EXPECT_TRUE(std::regex_search(
      state.output, std::regex("\njoint panda/panda_finger_joint2 position \\S+ velocity "
                               "\\S+ effort \\S+ leader panda/panda_finger_joint1\n")))
      << state.output;
  const ProcessResult follower =
      rbctl({"robot", "command", "panda", "--joint", "panda_finger_joint2", "--mode", "position",
             "--position", "0.01", "--stiffness", "100", "--damping", "1"});
  expectExitStatus(follower, 1);
  EXPECT_NE(follower.output.find("panda_finger_joint2"), std::string::npos) << follower.output;
  expectExitStatus(rbctl({"robot", "command", "panda", "--joint",
                          "panda_finger_joint1,panda_finger_joint2", "--mode", "position,keep",
                          "--position", "0.01", "--stiffness", "2000", "--damping", "60"}),
                   0);
}

}  // namespace
}  // namespace rbsim::e2e
