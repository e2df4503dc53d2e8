// rbserver --record FILE: an LCM event log holding every message the server
// published and received, read back with LCM's eventlog C API.

#include <gtest/gtest.h>

#include <rbsim/ack_t.hpp>
#include <rbsim/status_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <rbsim/world_t.hpp>
#include <rbsim/wrench_t.hpp>
#include <set>

#include "e2e_paths.h"
#include "event_log.h"
#include "rbsim/client/lookup.h"
#include "rigid_body_math.h"
#include "server_test.h"

namespace rbsim::e2e {
namespace {

using Record = ServerTest;

struct StateSteps {
  std::set<int64_t> steps;
  int undecodable = 0;
  int incomplete = 0;  // multi-page states are not expected in these small worlds
};

StateSteps stateStepsIn(const EventLog& log) {
  StateSteps out;
  for (const auto& event : log.events) {
    if (event.channel != "RBSIM_STATE") continue;
    const auto state = decodeAs<rbsim::world_state_t>(event);
    if (!state) {
      ++out.undecodable;
      continue;
    }
    if (state->num_pages != 1 || state->num_bodies != state->total_bodies) ++out.incomplete;
    out.steps.insert(state->step);
  }
  return out;
}

// Every event whole and numbered 0, 1, 2, ... and the file read to its end.
void expectWellFormed(const EventLog& log) {
  ASSERT_TRUE(log.opened);
  ASSERT_FALSE(log.events.empty());
  EXPECT_EQ(log.bytesParsed, log.fileSize) << "the file ends with a partial event";
  for (std::size_t i = 0; i < log.events.size(); ++i)
    ASSERT_EQ(log.events[i].eventNumber, static_cast<int64_t>(i))
        << "event numbers must be consecutive";
}

TEST_F(Record, LogHoldsEveryStateOfADurationRun) {
  const std::string path = scratchPath("run.lcmlog");
  const ProcessResult run = runProcess(
      {kRbserver, "--config", std::string(kWorldsDir) + "/free_bodies.yaml", "--lcm-url", kUrl,
       "--state-rate", "0", "--real-time-factor", "0", "--duration", "1", "--record", path},
      scratchPath("rbserver.log"), 60s);
  ASSERT_TRUE(run.status.has_value()) << "rbserver --duration 1 did not end\n" << run.output;
  ASSERT_EQ(*run.status, 0) << run.output;

  const EventLog log = readEventLog(path);
  expectWellFormed(log);
  const StateSteps states = stateStepsIn(log);
  EXPECT_EQ(states.undecodable, 0);
  EXPECT_EQ(states.incomplete, 0);
  // dt = 1 ms for 1 s: steps 0 (the initial state) to 1000, none missing.
  ASSERT_FALSE(states.steps.empty());
  EXPECT_EQ(*states.steps.begin(), 0);
  EXPECT_EQ(*states.steps.rbegin(), 1000);
  EXPECT_EQ(states.steps.size(), 1001u) << "a step is missing from the log";

  bool world = false, status = false;
  for (const auto& event : log.events) {
    if (event.channel == "RBSIM_WORLD") world |= decodeAs<rbsim::world_t>(event).has_value();
    if (event.channel == "RBSIM_STATUS") status |= decodeAs<rbsim::status_t>(event).has_value();
  }
  EXPECT_TRUE(world) << "the world description published at start is recorded";
  EXPECT_TRUE(status);
}

TEST_F(Record, SigtermExitsZeroWithACompleteLog) {
  const std::string path = scratchPath("session.lcmlog");
  startServer("free_bodies.yaml", {"--state-rate", "0", "--record", path});
  waitFor("100 steps", [&] { return currentStep() >= 100; });

  // A wrench received is recorded too, with its ack.
  client::Wrench push;
  push.body = "ball";
  push.force = {0.0, 0.0, 1.0};
  push.point = toVec3(client::findBody(*client().latestState(), "ball")->position);
  const client::Request request = client().applyWrench(push);
  expectAccepted(request);

  const auto status = stopServer(10s);
  ASSERT_TRUE(status.has_value()) << "rbserver did not stop on SIGTERM";
  EXPECT_EQ(*status, 0);

  const EventLog log = readEventLog(path);
  expectWellFormed(log);
  const StateSteps states = stateStepsIn(log);
  EXPECT_EQ(states.undecodable, 0);
  ASSERT_FALSE(states.steps.empty());
  const int64_t last = *states.steps.rbegin();
  EXPECT_GE(last, 100);
  EXPECT_EQ(*states.steps.begin(), 0);
  EXPECT_EQ(static_cast<int64_t>(states.steps.size()), last + 1)
      << "a step is missing from the log";

  bool wrenchRecorded = false, ackRecorded = false;
  std::optional<rbsim::status_t> lastStatus;
  for (const auto& event : log.events) {
    if (event.channel == "RBSIM_WRENCH")
      if (const auto w = decodeAs<rbsim::wrench_t>(event))
        wrenchRecorded |= w->client == client().clientId() && w->seq == request.seq;
    if (event.channel == "RBSIM_ACK")
      if (const auto a = decodeAs<rbsim::ack_t>(event))
        ackRecorded |= a->client == client().clientId() && a->seq == request.seq && a->accepted;
    if (event.channel == "RBSIM_STATUS") lastStatus = decodeAs<rbsim::status_t>(event);
  }
  EXPECT_TRUE(wrenchRecorded) << "the received wrench is in the log";
  EXPECT_TRUE(ackRecorded) << "its ack is in the log";
  ASSERT_TRUE(lastStatus.has_value());
  EXPECT_EQ(lastStatus->step, last) << "the last status (published at exit) matches the last state";
}

}  // namespace
}  // namespace rbsim::e2e
