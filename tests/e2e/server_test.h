#pragma once
// The fixture of the end-to-end tests that talk to a running rbserver: it
// starts the server as a separate process on a world from tests/e2e/worlds,
// connects a client (with a StateHistory), and stops the server at the end,
// failing the test if the server died on its own. Its output is printed when
// a test fails.
//
// Helpers that cannot go on after a failure (no ack, no state) throw
// std::runtime_error, which GoogleTest reports as a failure of the test.

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <rbsim/ack_t.hpp>
#include <rbsim/body_description_t.hpp>
#include <string>
#include <vector>

#include "child_process.h"
#include "rbsim/client/client.h"
#include "state_history.h"

namespace rbsim::e2e {

using namespace std::chrono_literals;

// Generous: ctest runs two tests at once on two cores, beside compilers.
inline constexpr std::chrono::milliseconds kAnswerTimeout = 5s;

class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  // Starts rbserver --config worlds/<world> (or `world` if it is an absolute
  // path) --lcm-url kUrl <arguments> and
  // waits for its first state and world description.
  void startServer(const std::string& world, const std::vector<std::string>& arguments);
  client::Client& client() { return *m_client; }
  StateHistory& history() { return m_history; }
  ChildProcess& server() { return *m_server; }
  // SIGTERM; returns the server's exit status (nullopt if it did not end
  // within `timeout`). The fixture then expects it to have ended.
  std::optional<int> stopServer(std::chrono::milliseconds timeout);
  // Another client on the same bus, with its own id.
  std::unique_ptr<client::Client> makeClient(const std::string& id) const;
  // A path in this test's scratch directory.
  std::string scratchPath(const std::string& name) const { return m_scratch + "/" + name; }

  // The ack of `request`, which must be accepted / rejected.
  rbsim::ack_t expectAccepted(const client::Request& request, client::Client* via = nullptr);
  rbsim::ack_t expectRejected(const client::Request& request, client::Client* via = nullptr);
  // Handles messages until `done()` or throws after `timeout`, naming `what`.
  void waitFor(const std::string& what, const std::function<bool()>& done,
               std::chrono::milliseconds timeout = kAnswerTimeout);
  // Handles messages for `duration`, whatever comes.
  void spinFor(std::chrono::milliseconds duration);
  // Until the history holds the state of `step`.
  void waitForStep(int64_t step);
  // STEP n (the server must be paused), then waits for the state after the
  // last of them; returns the ack.
  rbsim::ack_t stepAndWait(int64_t n);
  // The latest state's step (a state must have arrived).
  int64_t currentStep() const { return m_client->latestState()->step; }
  const rbsim::body_description_t& description(const std::string& body) const;

 private:
  std::string m_scratch;
  std::unique_ptr<ChildProcess> m_server;
  bool m_stoppedByTest = false;
  std::unique_ptr<client::Client> m_client;
  StateHistory m_history;
};

}  // namespace rbsim::e2e
