// rbsim-spy --check: the lcm-spy launcher finds the jars and lcm-spy's own
// type database finds every rbsim type on the class path, headless.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "e2e_paths.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

class Spy : public ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    if (std::string(kTypesJar).empty()) GTEST_SKIP() << "no JDK at configure time: no types jar";
  }

  ProcessResult check(const std::vector<std::string>& arguments) {
    std::vector<std::string> argv = {kSpyLauncher, "--check"};
    argv.insert(argv.end(), arguments.begin(), arguments.end());
    return runProcess(argv, scratchPath("spy.log"), 60s);
  }

  // The struct names of lcmtypes/rbsim/*.lcm: what the spy must decode.
  static std::vector<std::string> contractTypes() {
    std::vector<std::string> types;
    const std::regex structName(R"(^\s*struct\s+(\w+))");
    for (const auto& entry : std::filesystem::directory_iterator(kLcmTypesDir)) {
      if (entry.path().extension() != ".lcm") continue;
      std::ifstream file(entry.path());
      std::string line;
      std::smatch match;
      while (std::getline(file, line))
        if (std::regex_search(line, match, structName)) types.push_back(match[1]);
    }
    return types;
  }
};

TEST_F(Spy, CheckFindsEveryRbsimType) {
  const auto types = contractTypes();
  ASSERT_GE(types.size(), 6u);
  const ProcessResult run = check({"--types-jar", kTypesJar});
  ASSERT_TRUE(run.status.has_value()) << run.output;
  EXPECT_EQ(*run.status, 0) << run.output;
  for (const auto& type : types)
    EXPECT_NE(run.output.find("ok   rbsim." + type + " fingerprint"), std::string::npos)
        << type << " not found by the spy:\n"
        << run.output;
  EXPECT_EQ(run.output.find("FAIL"), std::string::npos) << run.output;
}

TEST_F(Spy, CheckFailsWhenATypeIsMissing) {
  ASSERT_FALSE(std::string(kJarTool).empty());
  // The types jar without status_t.
  const std::string classes = scratchPath("classes");
  std::filesystem::create_directories(classes);
  std::filesystem::copy_file(kTypesJar, classes + "/types.jar");
  const ProcessResult unpack =
      runProcess({"/bin/sh", "-c",
                  "cd '" + classes + "' && '" + kJarTool +
                      "' xf types.jar && rm types.jar rbsim/status_t.class"},
                 scratchPath("jar.log"), 60s);
  ASSERT_EQ(unpack.status.value_or(-1), 0) << unpack.output;
  const std::string partial = scratchPath("partial.jar");
  const ProcessResult pack =
      runProcess({kJarTool, "cf", partial, "-C", classes, "."}, scratchPath("jar.log"), 60s);
  ASSERT_EQ(pack.status.value_or(-1), 0) << pack.output;

  const ProcessResult run = check({"--types-jar", partial});
  ASSERT_TRUE(run.status.has_value()) << run.output;
  EXPECT_NE(*run.status, 0) << run.output;
  EXPECT_NE(run.output.find("FAIL rbsim.status_t"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("ok   rbsim.world_state_t"), std::string::npos) << run.output;
}

TEST_F(Spy, CheckFailsWithoutTheTypesJar) {
  const ProcessResult run = check({"--types-jar", "/nonexistent/rbsim_types.jar"});
  ASSERT_TRUE(run.status.has_value()) << run.output;
  EXPECT_NE(*run.status, 0) << run.output;
  EXPECT_NE(run.output.find("types jar not found: /nonexistent/rbsim_types.jar"), std::string::npos)
      << run.output;
  // The same through the environment, as the build-tree launcher sets it.
  const ProcessResult viaEnvironment = runProcess({kSpyLauncher, "--check"}, scratchPath("spy.log"),
                                                  60s, {"RBSIM_TYPES_JAR=/nonexistent/other.jar"});
  EXPECT_NE(viaEnvironment.status.value_or(0), 0) << viaEnvironment.output;
  EXPECT_NE(viaEnvironment.output.find("/nonexistent/other.jar"), std::string::npos)
      << viaEnvironment.output;
}

}  // namespace
}  // namespace rbsim::e2e
