// Access control and limits of the command path over the bus: read-only
// mode, the wrench allowlist, the body limit and the per-client rate.

#include <gtest/gtest.h>

#include "server_test.h"

namespace rbsim::e2e {
namespace {

using Limits = ServerTest;

client::Wrench pushOn(const std::string& body) {
  client::Wrench w;
  w.body = body;
  w.force = {1.0, 0.0, 0.0};
  w.frame = client::Frame::Body;
  return w;
}

TEST_F(Limits, ReadOnlyServerRejectsEverythingAndStillPublishes) {
  startServer("limited.yaml", {"--read-only"});
  const rbsim::ack_t wrench = expectRejected(client().applyWrench(pushOn("ball")));
  EXPECT_NE(wrench.reason.find("read-only"), std::string::npos) << wrench.reason;
  const rbsim::ack_t pause = expectRejected(client().pause());
  EXPECT_NE(pause.reason.find("read-only"), std::string::npos) << pause.reason;
  const int64_t step = currentStep();
  waitFor("the state to move on", [&] { return currentStep() > step + 50; });
}

TEST_F(Limits, ConfigLimitsAreEnforced) {
  startServer("limited.yaml", {});
  expectAccepted(client().applyWrench(pushOn("ball")));
  const rbsim::ack_t box = expectRejected(client().applyWrench(pushOn("box")));
  EXPECT_NE(box.reason.find("does not accept external wrenches"), std::string::npos) << box.reason;

  expectAccepted(client().spawn("{name: third, shape: {type: sphere, radius: 0.1}, position: [0, 3, 0]}"));
  const rbsim::ack_t fourth =
      expectRejected(client().spawn("{name: fourth, shape: {type: sphere, radius: 0.1}, position: [0, -3, 0]}"));
  EXPECT_NE(fourth.reason.find("max_bodies"), std::string::npos) << fourth.reason;

  // A burst beyond client_burst: the excess is rejected at once, every
  // message answered, and another client is not affected.
  auto flooder = makeClient("e2e-flooder");
  std::vector<client::Request> sent;
  for (int i = 0; i < 120; ++i) sent.push_back(flooder->applyWrench(pushOn("ball")));
  int accepted = 0, limited = 0;
  for (const auto& request : sent) {
    const auto ack = flooder->waitForAck(request, kAnswerTimeout);
    ASSERT_TRUE(ack.has_value()) << "every message is answered";
    if (ack->accepted) ++accepted;
    if (!ack->accepted && ack->reason.find("rate limit") != std::string::npos) ++limited;
  }
  EXPECT_GE(accepted, 50);
  EXPECT_LT(accepted, 120);
  EXPECT_EQ(accepted + limited, 120);
  expectAccepted(client().applyWrench(pushOn("ball")));
}

}  // namespace
}  // namespace rbsim::e2e
