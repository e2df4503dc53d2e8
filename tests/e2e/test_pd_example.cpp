// The C++ PD example (clients/cpp/examples/pd_hold_height.cpp) against a
// server with gravity: it must hold the ball at the target height, as the
// example itself reports and as the test's own client sees.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "e2e_paths.h"
#include "rbsim/client/lookup.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

using PdExample = ServerTest;

TEST_F(PdExample, HoldsABodyAtTheTargetHeightUnderGravity) {
  startServer("gravity.yaml", {});  // real time, states at 100 Hz
  const double target = 1.0;        // m; the ball starts at 0.5 m and falls
  const double tolerance = 0.005;   // m

  // The example's wrenches come from client id "cpp-<host>-<pid>": its first
  // accepted push marks when it took over.
  std::string exampleSuffix;
  std::optional<int64_t> firstPush;
  client().onAck([&](const rbsim::ack_t& ack) {
    if (!firstPush && !exampleSuffix.empty() && ack.accepted &&
        ack.kind == rbsim::ack_t::KIND_WRENCH && ack.client.size() > exampleSuffix.size() &&
        ack.client.compare(ack.client.size() - exampleSuffix.size(), exampleSuffix.size(),
                           exampleSuffix) == 0)
      firstPush = ack.effective_step;
  });
  std::vector<std::pair<double, double>> heights;  // (sim time, z), watched while the example runs
  client().onState([&](const rbsim::world_state_t& state) {
    if (const auto* ball = client::findBody(state, "ball"))
      heights.emplace_back(state.sim_time, ball->position[2]);
  });

  ChildProcess example({kPdExample, "--url", kUrl, "--body", "ball", "--height", "1.0",
                        "--duration", "3.0", "--tolerance", "0.005"},
                       scratchPath("pd.log"));
  exampleSuffix = "-" + std::to_string(example.pid());
  waitFor(
      "the example to finish", [&] { return example.poll().has_value(); }, 60s);
  const int status = *example.poll();
  EXPECT_EQ(status, 0) << example.output();
  EXPECT_NE(example.output().find("final height"), std::string::npos) << example.output();
  ASSERT_TRUE(firstPush.has_value()) << "no accepted wrench from the example";

  // It controls for 3 s of simulated time from its first push, starting
  // below the target (the ball starts 0.5 m below and falls until then):
  // from 2 s to 2.8 s after that push the ball must be at the target.
  const double start = static_cast<double>(*firstPush) * client().world()->dt;
  int checked = 0;
  for (const auto& [time, z] : heights) {
    if (time < start + 2.0 || time > start + 2.8) continue;
    ++checked;
    EXPECT_NEAR(z, target, tolerance) << "at t = " << time << " s";
  }
  EXPECT_GT(checked, 20) << "too few states seen in the settled window";
}

}  // namespace
}  // namespace rbsim::e2e
