// rbserver refuses bad input before it steps: a clear message naming what is
// wrong, a non-zero exit, and not one state on the bus. It warns at start
// about a world it cannot follow, and not about the default world.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "e2e_paths.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

class Startup : public ServerTest {
 protected:
  // Runs rbserver with `arguments` while a client listens on the bus; the
  // server must fail. Returns its output.
  std::string expectFailure(const std::vector<std::string>& arguments) {
    client::ClientOptions options;
    options.url = kUrl;
    client::Client listener(options);
    EXPECT_TRUE(listener.good());
    std::vector<std::string> argv = {kRbserver};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    const ProcessResult run = runProcess(argv, scratchPath("rbserver.log"), 10s);
    EXPECT_TRUE(run.status.has_value()) << "rbserver did not stop by itself";
    EXPECT_NE(run.status.value_or(0), 0) << run.output;
    EXPECT_LT(run.status.value_or(0), 128) << "it must exit, not crash:\n" << run.output;
    listener.spinUntil([] { return false; }, 100ms);
    EXPECT_EQ(listener.stateCount(), 0u) << "it published states before failing";
    EXPECT_EQ(listener.statusCount(), 0u);
    EXPECT_NE(run.output.find("rbserver: "), std::string::npos)
        << "messages start with the program name";
    return run.output;
  }

  std::string writeConfig(const std::string& name, const std::string& text) {
    const std::string path = scratchPath(name);
    std::ofstream(path) << text;
    return path;
  }

  static std::string world() { return std::string(kWorldsDir) + "/free_bodies.yaml"; }
};

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE((text).find(part), std::string::npos) << "expected \"" << (part) << "\" in:\n" << (text)

TEST_F(Startup, MissingConfigFile) {
  const std::string output = expectFailure({"--config", "/nonexistent/world.yaml"});
  EXPECT_CONTAINS(output, "/nonexistent/world.yaml");
  EXPECT_CONTAINS(output, "No such file");
}

TEST_F(Startup, InvalidConfigValueNamesFileLineAndKey) {
  const std::string bad = writeConfig("bad_dt.yaml",
                                      "world:\n  dt: -0.001\nbodies:\n"
                                      "  - {name: ball, shape: {type: sphere, radius: 0.1}}\n");
  const std::string output = expectFailure({"--config", bad});
  EXPECT_CONTAINS(output, bad + ":2:");
  EXPECT_CONTAINS(output, "world.dt");
}

TEST_F(Startup, YamlSyntaxErrorAndUnknownKey) {
  EXPECT_CONTAINS(expectFailure({"--config", writeConfig("syntax.yaml", "world: {dt: 0.001\n")}),
                  "syntax.yaml:");
  const std::string output = expectFailure(
      {"--config", writeConfig("unknown.yaml", "world: {dt: 0.001, colour: red}\nbodies: []\n")});
  EXPECT_CONTAINS(output, "colour");
}

TEST_F(Startup, BadLcmUrl) {
  const std::string output = expectFailure({"--config", world(), "--lcm-url", "nosuch://anywhere"});
  EXPECT_CONTAINS(output, "cannot open LCM");
  EXPECT_CONTAINS(output, "nosuch://anywhere");
  EXPECT_CONTAINS(expectFailure({"--config", world(), "--lcm-url", "udpm://239.255.76.67:99999"}),
                  "cannot open LCM");
}

TEST_F(Startup, BadCommandLine) {
  EXPECT_CONTAINS(expectFailure({"--config", world(), "--real-time-factor", "fast"}),
                  "--real-time-factor");
  EXPECT_CONTAINS(expectFailure({"--config", world(), "--frobnicate"}), "--frobnicate");
  EXPECT_CONTAINS(expectFailure({"--paused"}), "--config");
  EXPECT_CONTAINS(expectFailure({"--config", world(), "--channel-prefix", "A.*"}), "prefix");
  for (const char* threads : {"-1", "1.5", "257", "many"})
    EXPECT_CONTAINS(expectFailure({"--config", world(), "--threads", threads}), "--threads");
}

TEST_F(Startup, ABadThreadCountInTheFileNamesFileLineAndKey) {
  const std::string bad = writeConfig("bad_threads.yaml",
                                      "world:\n  dt: 0.001\n  threads: 2.5\nbodies:\n"
                                      "  - {name: ball, shape: {type: sphere, radius: 0.1}}\n");
  const std::string output = expectFailure({"--config", bad});
  EXPECT_CONTAINS(output, bad + ":3:");
  EXPECT_CONTAINS(output, "threads");
}

TEST_F(Startup, UnwritableRecordFile) {
  const std::string output = expectFailure(
      {"--config", world(), "--lcm-url", kUrl, "--record", "/nonexistent-dir/run.lcmlog"});
  EXPECT_CONTAINS(output, "/nonexistent-dir/run.lcmlog");
}

TEST_F(Startup, WarnsThatTheEulerMethodsLoseAFastTop) {
  // A disc nutating at 188 rad/s: either Euler method at 1 ms gains 1% of its
  // energy within a tenth of a second. The server says so, naming the body,
  // and runs anyway.
  const auto run = [&](const std::string& integrator) {
    const std::string config = writeConfig(
        "top_" + integrator + ".yaml",
        "world: {dt: 0.001, gravity: [0, 0, 0], integrator: " + integrator + "}\n"
        "bodies:\n"
        "  - {name: top, shape: {type: cylinder, radius: 0.05, half_length: 0.02}, mass: 1.0,\n"
        "     angular_velocity: [9.4, 0, 187.76]}\n"
        "  - {name: slow, shape: {type: box, half_extents: [0.1, 0.2, 0.3]}, position: [1, 0, 0],\n"
        "     angular_velocity: [0.1, 0.2, 0.3]}\n");
    const ProcessResult result =
        runProcess({kRbserver, "--config", config, "--lcm-url", kUrl, "--state-rate", "0",
                    "--real-time-factor", "0", "--duration", "1"},
                   scratchPath("rbserver.log"), 60s);
    EXPECT_EQ(result.status.value_or(-1), 0) << result.output;
    return result.output;
  };
  const std::string output = run("explicit_euler");
  EXPECT_CONTAINS(output,
                  "WARNING body 'top' spins at |w| = 188 rad/s: explicit Euler at dt = 0.001 s");
  EXPECT_CONTAINS(output, "rk4");
  EXPECT_EQ(output.find("'slow'"), std::string::npos) << output;
  EXPECT_CONTAINS(run("semi_implicit_euler"),
                  "WARNING body 'top' spins at |w| = 188 rad/s: semi-implicit Euler at dt = 0.001 s");
  EXPECT_EQ(run("rk4").find("WARNING body"), std::string::npos);
}

TEST_F(Startup, TheDefaultWorldStartsWithoutAWarning) {
  // The world a newcomer runs first, as the README runs it (paced, no
  // --duration: the spin check looks 10 s ahead). A warning about its own
  // bodies would teach them to ignore warnings.
  startServer(kDefaultWorld, {});
  spinFor(500ms);  // past the start log, into stepping
  const std::string output = server().output();
  EXPECT_CONTAINS(output, "stepping 15 bodies");
  EXPECT_EQ(output.find("WARNING"), std::string::npos) << output;
  EXPECT_EQ(output.find("ERROR"), std::string::npos) << output;
  EXPECT_EQ(stopServer(5s).value_or(-1), 0) << server().output();
}

}  // namespace
}  // namespace rbsim::e2e
