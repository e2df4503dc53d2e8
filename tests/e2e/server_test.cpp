#include "server_test.h"

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "e2e_paths.h"
#include "rbsim/client/lookup.h"

namespace rbsim::e2e {

void ServerTest::SetUp() {
  char pattern[] = "/tmp/rbsim-e2e-XXXXXX";
  if (mkdtemp(pattern) == nullptr) throw std::runtime_error("mkdtemp failed");
  m_scratch = pattern;
}

void ServerTest::TearDown() {
  if (m_server && !m_stoppedByTest) {
    const auto early = m_server->poll();
    const int status = early ? *early : m_server->stop(5s);
    if (early) ADD_FAILURE() << "rbserver ended during the test with status " << *early;
    if (!early && status != 0)
      ADD_FAILURE() << "rbserver exited with status " << status << " on SIGTERM";
  }
  if (m_server && HasFailure())
    std::fprintf(stderr, "---- %s\n%s---- end of rbserver output\n",
                 m_server->commandLine().c_str(), m_server->output().c_str());
  m_client.reset();
  m_server.reset();
  if (HasFailure()) {
    std::fprintf(stderr, "scratch files kept in %s\n", m_scratch.c_str());
  } else {
    std::filesystem::remove_all(m_scratch);
  }
}

void ServerTest::startServer(const std::string& world, const std::vector<std::string>& arguments) {
  // Connect first, so that the world description published at start is not missed.
  client::ClientOptions options;
  options.url = kUrl;
  options.clientId = "e2e-main";
  m_client = std::make_unique<client::Client>(options);
  if (!m_client->good()) throw std::runtime_error(std::string("cannot open LCM at ") + kUrl);
  m_history.attach(*m_client);

  const std::string config = world.starts_with('/') ? world : std::string(kWorldsDir) + "/" + world;
  std::vector<std::string> argv = {kRbserver, "--config", config, "--lcm-url", kUrl};
  argv.insert(argv.end(), arguments.begin(), arguments.end());
  m_server = std::make_unique<ChildProcess>(argv, scratchPath("rbserver.log"));
  waitFor(
      "the server's first state", [&] { return m_client->latestState().has_value(); }, 10s);
  if (!m_client->world()) m_client->publishWorld();
  waitFor("the world description", [&] { return m_client->world().has_value(); });
}

std::optional<int> ServerTest::stopServer(std::chrono::milliseconds timeout) {
  m_stoppedByTest = true;
  m_server->signal(SIGTERM);
  return m_server->wait(timeout);
}

std::unique_ptr<client::Client> ServerTest::makeClient(const std::string& id) const {
  client::ClientOptions options;
  options.url = kUrl;
  options.clientId = id;
  return std::make_unique<client::Client>(options);
}

rbsim::ack_t ServerTest::expectAccepted(const client::Request& request, client::Client* via) {
  client::Client& sender = via != nullptr ? *via : *m_client;
  const auto ack = sender.waitForAck(request, kAnswerTimeout);
  if (!ack)
    throw std::runtime_error("no ack for seq " + std::to_string(request.seq) + " of " +
                             sender.clientId());
  if (!ack->accepted)
    throw std::runtime_error("seq " + std::to_string(request.seq) + " rejected: " + ack->reason);
  EXPECT_EQ(ack->client, sender.clientId());
  EXPECT_EQ(ack->seq, request.seq);
  EXPECT_EQ(ack->kind, static_cast<int8_t>(request.kind));
  return *ack;
}

rbsim::ack_t ServerTest::expectRejected(const client::Request& request, client::Client* via) {
  client::Client& sender = via != nullptr ? *via : *m_client;
  const auto ack = sender.waitForAck(request, kAnswerTimeout);
  if (!ack)
    throw std::runtime_error("no ack for seq " + std::to_string(request.seq) + " of " +
                             sender.clientId());
  EXPECT_FALSE(ack->accepted) << "seq " << request.seq << " was accepted";
  EXPECT_FALSE(ack->reason.empty()) << "a rejection must say why";
  EXPECT_EQ(ack->effective_step, -1);
  EXPECT_EQ(ack->seq, request.seq);
  EXPECT_EQ(ack->kind, static_cast<int8_t>(request.kind));
  return *ack;
}

void ServerTest::waitFor(const std::string& what, const std::function<bool()>& done,
                         std::chrono::milliseconds timeout) {
  // Give up at once if the server died: nothing will come any more.
  const auto serverEnded = [&] { return m_server && !m_stoppedByTest && m_server->poll(); };
  if (m_client->spinUntil([&] { return done() || serverEnded(); }, timeout) && done()) return;
  if (serverEnded())
    throw std::runtime_error("rbserver ended with status " + std::to_string(*m_server->poll()) +
                             " while the test waited for " + what);
  throw std::runtime_error("timed out after " + std::to_string(timeout.count()) +
                           " ms waiting for " + what);
}

void ServerTest::spinFor(std::chrono::milliseconds duration) {
  m_client->spinUntil([] { return false; }, duration);
}

void ServerTest::waitForStep(int64_t step) {
  waitFor("the state of step " + std::to_string(step), [&] { return m_history.has(step); });
}

rbsim::ack_t ServerTest::stepAndWait(int64_t n) {
  const rbsim::ack_t ack = expectAccepted(m_client->step(n));
  waitForStep(ack.effective_step + n - 1);
  return ack;
}

const rbsim::body_description_t& ServerTest::description(const std::string& body) const {
  const auto* found = client::findBody(*m_client->world(), body);
  if (found == nullptr)
    throw std::runtime_error("the world description has no body '" + body + "'");
  return *found;
}

}  // namespace rbsim::e2e
