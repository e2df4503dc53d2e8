// Bad requests are rejected with a reason, answered like any other (one ack
// each), and never stop the server: after each one it keeps stepping.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <rbsim/command_t.hpp>
#include <rbsim/wrench_t.hpp>
#include <vector>

#include "rbsim/client/lookup.h"
#include "rigid_body_math.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

class Rejections : public ServerTest {
 protected:
  void SetUp() override {
    ServerTest::SetUp();
    startServer("free_bodies.yaml", {});  // running, real time
    m_initialPuckVelocity =
        toVec3(client::findBody(*client().latestState(), "puck")->linear_velocity);
  }

  Vec3 m_initialPuckVelocity{};

  void expectStillStepping() {
    const int64_t now = currentStep();
    waitFor("the server to keep stepping", [&] { return currentStep() >= now + 30; });
  }

  client::Wrench pushOn(const std::string& body) {
    client::Wrench wrench;
    wrench.body = body;
    wrench.force = {1.0, 0.0, 0.0};
    if (const auto* state = client::findBody(*client().latestState(), body))
      wrench.point = toVec3(state->position);
    return wrench;
  }

  // Collects the acks that answer no client: those of undecodable messages.
  std::vector<rbsim::ack_t> m_anonymousAcks;
  void collectAnonymousAcks() {
    client().onAck([this](const rbsim::ack_t& ack) {
      if (ack.client.empty()) m_anonymousAcks.push_back(ack);
    });
  }
};

TEST_F(Rejections, UnknownBody) {
  const rbsim::ack_t ack = expectRejected(client().applyWrench(pushOn("no_such_body")));
  EXPECT_NE(ack.reason.find("no_such_body"), std::string::npos) << ack.reason;
  EXPECT_EQ(ack.request, rbsim::wrench_t::MODE_ONE_STEP);
  expectRejected(client().remove("no_such_body"));
  expectStillStepping();
}

TEST_F(Rejections, NonFiniteForceOrTorque) {
  client::Wrench nanForce = pushOn("puck");
  nanForce.force[1] = std::numeric_limits<double>::quiet_NaN();
  const rbsim::ack_t ack = expectRejected(client().applyWrench(nanForce));
  EXPECT_NE(ack.reason.find("finite"), std::string::npos) << ack.reason;

  client::Wrench infiniteTorque = pushOn("puck");
  infiniteTorque.torque[2] = std::numeric_limits<double>::infinity();
  expectRejected(client().applyWrench(infiniteTorque));
  expectStillStepping();
  // Nothing of them reached the body: the puck still moves at its initial velocity.
  EXPECT_EQ(toVec3(client::findBody(*client().latestState(), "puck")->linear_velocity),
            m_initialPuckVelocity);
}

TEST_F(Rejections, WrenchScheduledInThePast) {
  waitFor("a few steps", [&] { return currentStep() >= 10; });
  client::Wrench late = pushOn("puck");
  late.applyAtStep = currentStep();  // already taken
  const rbsim::ack_t ack = expectRejected(client().applyWrench(late));
  EXPECT_NE(ack.reason.find("past"), std::string::npos) << ack.reason;
  late.applyAtStep = -7;
  expectRejected(client().applyWrench(late));
  expectStillStepping();
}

TEST_F(Rejections, GarbageOnTheWrenchChannel) {
  collectAnonymousAcks();
  const std::string garbage = "certainly not an LCM message";
  client().lcm().publish(client().channel("WRENCH"), garbage.data(),
                         static_cast<unsigned>(garbage.size()));
  // The right fingerprint, cut short.
  rbsim::wrench_t wrench{};
  wrench.client = "e2e-truncated";
  wrench.body = "puck";
  std::vector<uint8_t> bytes(static_cast<std::size_t>(wrench.getEncodedSize()));
  wrench.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  client().lcm().publish(client().channel("WRENCH"), bytes.data(),
                         static_cast<unsigned>(bytes.size() - 9));

  waitFor("two acks for the undecodable wrenches", [&] { return m_anonymousAcks.size() >= 2; });
  for (const auto& ack : m_anonymousAcks) {
    EXPECT_FALSE(ack.accepted);
    EXPECT_EQ(ack.kind, rbsim::ack_t::KIND_WRENCH);
    EXPECT_EQ(ack.seq, -1);
    EXPECT_NE(ack.reason.find("undecodable"), std::string::npos) << ack.reason;
  }
  expectStillStepping();
  // And it still takes well-formed requests.
  expectAccepted(client().applyWrench(pushOn("puck")));
}

TEST_F(Rejections, GarbageOnTheCommandChannel) {
  collectAnonymousAcks();
  const std::vector<uint8_t> garbage(300, 0xAB);
  client().lcm().publish(client().channel("COMMAND"), garbage.data(),
                         static_cast<unsigned>(garbage.size()));
  waitFor("the ack of the undecodable command", [&] { return !m_anonymousAcks.empty(); });
  const rbsim::ack_t& ack = m_anonymousAcks.front();
  EXPECT_FALSE(ack.accepted);
  EXPECT_EQ(ack.kind, rbsim::ack_t::KIND_COMMAND);
  EXPECT_NE(ack.reason.find("undecodable"), std::string::npos) << ack.reason;
  // A decodable command with a number that is no command.
  rbsim::command_t unknown{};
  unknown.client = client().clientId();
  unknown.seq = 424242;
  unknown.command = 0;  // deliberately not a command
  client().lcm().publish(client().channel("COMMAND"), &unknown);
  const auto answer = client().waitForAck(unknown.seq, client::AckKind::Command, kAnswerTimeout);
  ASSERT_TRUE(answer.has_value());
  EXPECT_FALSE(answer->accepted);
  EXPECT_FALSE(answer->reason.empty());

  expectStillStepping();
  waitFor("a status counting the rejections", [&] {
    return client().latestStatus() && client().latestStatus()->commands_rejected >= 2;
  });
  expectAccepted(client().publishWorld());
}

}  // namespace
}  // namespace rbsim::e2e
