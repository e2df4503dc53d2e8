// The soak test's judge: compares the server's record file with what each
// load client says it sent and received, and prints the figures.
//
//   soak_check --record FILE --state-every STEPS CLIENT_LOG...
//
// A client log (written by soak_client / soak_client.py) is text, one item a
// line:
//   client ID
//   sent W|C SEQ WHAT        a wrench (W) or command (C) the client published
//   ack W|C SEQ 0|1          an ack of its own it received (accepted or not)
//   state STEP UTIME         a complete state it received
//
// Asserted (exit status 1 and a FAIL line for each broken rule):
//  - the record file is whole: every byte parsed, event numbers 0, 1, 2, ...;
//  - every message a client sent was received by the server exactly once
//    (it is in the record once) and acknowledged exactly once (one ack_t
//    with the same client, kind and seq); no ack answers an unsent message;
//    the server's accepted + rejected counters equal the acks it published;
//  - every ack a client received is in the record with the same verdict,
//    and no client received one of its acks twice; at least 99% of them
//    arrived (UDP may drop; the record may not);
//  - every state in the record is whole (pages 0 .. n-1, once each), steps
//    never go back, and every step that is a multiple of --state-every from
//    the first state to the last is there; every state a client received is
//    in the record.
// Reported, not asserted (the machine may be loaded): overruns, step times,
// real-time factor.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <rbsim/ack_t.hpp>
#include <rbsim/command_t.hpp>
#include <rbsim/status_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <rbsim/wrench_t.hpp>

#include "event_log.h"

namespace {

using rbsim::e2e::decodeAs;

// (client, kind 'W' or 'C', seq)
using MessageKey = std::tuple<std::string, char, int64_t>;
// (step, utime): a state's identity (all its pages share both)
using StateKey = std::pair<int64_t, int64_t>;

struct ClientLog {
  std::string id;
  std::vector<std::pair<char, int64_t>> sent;
  std::map<std::pair<char, int64_t>, std::string> sentWhat;
  std::vector<std::tuple<char, int64_t, bool>> acks;
  std::vector<StateKey> states;
};

bool readClientLog(const std::string& path, ClientLog& log) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "client") {
      words >> log.id;
    } else if (tag == "sent") {
      char kind = 0;
      int64_t seq = 0;
      std::string what;
      words >> kind >> seq >> what;
      log.sent.emplace_back(kind, seq);
      log.sentWhat[{kind, seq}] = what;
    } else if (tag == "ack") {
      char kind = 0;
      int64_t seq = 0;
      int accepted = 0;
      words >> kind >> seq >> accepted;
      log.acks.emplace_back(kind, seq, accepted != 0);
    } else if (tag == "state") {
      int64_t step = 0, utime = 0;
      words >> step >> utime;
      log.states.emplace_back(step, utime);
    }
  }
  return !log.id.empty();
}

class Verdict {
 public:
  void fail(const std::string& what) {
    ++m_failures;
    if (m_failures <= 40) std::printf("FAIL %s\n", what.c_str());
  }
  int failures() const { return m_failures; }

 private:
  int m_failures = 0;
};

struct AckRecord {
  int count = 0;
  bool accepted = false;
  std::string reason;
};

struct StatePages {
  int32_t numPages = 0;
  std::vector<int> seen;  // per page index
};

char kindLetter(int8_t kind) { return kind == rbsim::ack_t::KIND_WRENCH ? 'W' : 'C'; }

std::string describe(const MessageKey& key) {
  return std::get<0>(key) + " " + std::get<1>(key) + " seq " + std::to_string(std::get<2>(key));
}

}  // namespace

int main(int argc, char** argv) {
  std::string recordPath, prefix = "RBSIM_";
  int64_t stateEvery = 0;
  std::vector<std::string> clientPaths;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--record" && i + 1 < argc) recordPath = argv[++i];
    else if (arg == "--state-every" && i + 1 < argc) stateEvery = std::stoll(argv[++i]);
    else if (arg == "--prefix" && i + 1 < argc) prefix = argv[++i];
    else clientPaths.push_back(arg);
  }
  if (recordPath.empty() || stateEvery <= 0 || clientPaths.empty()) {
    std::fprintf(stderr, "usage: soak_check --record FILE --state-every STEPS [--prefix P] CLIENT_LOG...\n");
    return 2;
  }
  Verdict verdict;

  // --- the record file ---------------------------------------------------
  const rbsim::e2e::EventLog log = rbsim::e2e::readEventLog(recordPath);
  if (!log.opened) {
    std::printf("FAIL cannot open the record file %s\n", recordPath.c_str());
    return 1;
  }
  if (log.bytesParsed != log.fileSize)
    verdict.fail("record file: parsed " + std::to_string(log.bytesParsed) + " of " +
                 std::to_string(log.fileSize) + " bytes");
  for (std::size_t i = 0; i < log.events.size(); ++i)
    if (log.events[i].eventNumber != static_cast<int64_t>(i)) {
      verdict.fail("record file: event " + std::to_string(i) + " is numbered " +
                   std::to_string(log.events[i].eventNumber));
      break;
    }

  std::map<MessageKey, int> received;
  std::map<MessageKey, AckRecord> acks;
  std::map<StateKey, StatePages> states;
  std::vector<StateKey> stateOrder;
  std::vector<rbsim::status_t> statuses;
  int64_t ackEvents = 0, undecodable = 0;
  for (const auto& event : log.events) {
    if (event.channel == prefix + "WRENCH") {
      if (const auto m = decodeAs<rbsim::wrench_t>(event)) ++received[{m->client, 'W', m->seq}];
      else ++undecodable;
    } else if (event.channel == prefix + "COMMAND") {
      if (const auto m = decodeAs<rbsim::command_t>(event)) ++received[{m->client, 'C', m->seq}];
      else ++undecodable;
    } else if (event.channel == prefix + "ACK") {
      ++ackEvents;
      if (const auto m = decodeAs<rbsim::ack_t>(event)) {
        AckRecord& record = acks[{m->client, kindLetter(m->kind), m->seq}];
        ++record.count;
        record.accepted = m->accepted;
        record.reason = m->reason;
      } else {
        ++undecodable;
      }
    } else if (event.channel == prefix + "STATE") {
      const auto page = decodeAs<rbsim::world_state_t>(event);
      if (!page) {
        ++undecodable;
        continue;
      }
      const StateKey key{page->step, page->utime};
      StatePages& pages = states[key];
      if (pages.seen.empty()) {
        stateOrder.push_back(key);
        pages.numPages = page->num_pages;
        pages.seen.assign(static_cast<std::size_t>(std::max(0, page->num_pages)), 0);
      }
      if (page->num_pages != pages.numPages || page->page < 0 || page->page >= pages.numPages)
        verdict.fail("state of step " + std::to_string(page->step) + ": inconsistent page " +
                     std::to_string(page->page) + " of " + std::to_string(page->num_pages));
      else
        ++pages.seen[static_cast<std::size_t>(page->page)];
    } else if (event.channel == prefix + "STATUS") {
      if (const auto m = decodeAs<rbsim::status_t>(event)) statuses.push_back(*m);
      else ++undecodable;
    }
  }
  if (undecodable > 0) verdict.fail(std::to_string(undecodable) + " record events do not decode");

  // --- every message received once and acked once -------------------------
  std::set<MessageKey> sentKeys;
  int64_t sentWrenches = 0, sentCommands = 0, clientAcksExpected = 0, clientAcksReceived = 0;
  int64_t clientStates = 0, accepted = 0, rejected = 0;
  std::map<std::string, int64_t> commandsByKind;
  std::vector<std::string> clientSummaries;
  for (const std::string& path : clientPaths) {
    ClientLog client;
    if (!readClientLog(path, client)) {
      verdict.fail("cannot read client log " + path);
      continue;
    }
    int64_t ownAcksReceived = 0;
    for (const auto& [kind, seq] : client.sent) {
      const MessageKey key{client.id, kind, seq};
      if (!sentKeys.insert(key).second) verdict.fail("sent twice with one seq: " + describe(key));
      (kind == 'W' ? sentWrenches : sentCommands) += 1;
      if (kind == 'C') ++commandsByKind[client.sentWhat[{kind, seq}]];
      const auto got = received.find(key);
      const int times = got == received.end() ? 0 : got->second;
      if (times != 1) verdict.fail(describe(key) + " is in the record " + std::to_string(times) + " times");
      const auto ack = acks.find(key);
      const int ackCount = ack == acks.end() ? 0 : ack->second.count;
      if (ackCount != 1) verdict.fail(describe(key) + " was acknowledged " + std::to_string(ackCount) + " times");
      if (ack != acks.end()) (ack->second.accepted ? accepted : rejected) += 1;
    }
    std::set<std::pair<char, int64_t>> seenAcks;
    for (const auto& [kind, seq, wasAccepted] : client.acks) {
      const MessageKey key{client.id, kind, seq};
      if (!seenAcks.insert({kind, seq}).second) verdict.fail("client received an ack twice: " + describe(key));
      const auto ack = acks.find(key);
      if (ack == acks.end()) verdict.fail("client received an ack the record does not hold: " + describe(key));
      else if (ack->second.accepted != wasAccepted) verdict.fail("ack verdicts differ for " + describe(key));
      ++ownAcksReceived;
    }
    clientAcksExpected += static_cast<int64_t>(client.sent.size());
    clientAcksReceived += ownAcksReceived;
    for (const StateKey& key : client.states) {
      const auto found = states.find(key);
      if (found == states.end())
        verdict.fail("client " + client.id + " received the state of step " + std::to_string(key.first) +
                     " (utime " + std::to_string(key.second) + ") that the record does not hold");
    }
    clientStates += static_cast<int64_t>(client.states.size());
    const double share = client.sent.empty() ? 1.0 : static_cast<double>(ownAcksReceived) / static_cast<double>(client.sent.size());
    if (share < 0.99)
      verdict.fail("client " + client.id + " received only " + std::to_string(ownAcksReceived) + " of its " +
                   std::to_string(client.sent.size()) + " acks");
    char summary[256];
    std::snprintf(summary, sizeof summary, "%s: sent %zu, acks received %lld (%.3f%%), states received %zu",
                  client.id.c_str(), client.sent.size(), static_cast<long long>(ownAcksReceived), 100.0 * share,
                  client.states.size());
    clientSummaries.emplace_back(summary);
  }
  for (const auto& [key, record] : acks) {
    if (std::get<0>(key).empty()) continue;  // an undecodable message: not ours
    if (!sentKeys.count(key)) verdict.fail("ack for a message no client sent: " + describe(key));
  }
  for (const auto& [key, count] : received)
    if (!sentKeys.count(key)) verdict.fail("the record holds a message no client sent: " + describe(key));

  // --- states --------------------------------------------------------------
  int64_t wholeStates = 0;
  int64_t previousStep = -1;
  std::set<int64_t> steps;
  for (const StateKey& key : stateOrder) {
    const StatePages& pages = states[key];
    const bool whole = pages.numPages > 0 &&
                       std::all_of(pages.seen.begin(), pages.seen.end(), [](int n) { return n == 1; });
    if (whole) ++wholeStates;
    else verdict.fail("state of step " + std::to_string(key.first) + " is not whole in the record");
    if (key.first < previousStep)
      verdict.fail("state steps go back: " + std::to_string(previousStep) + " then " + std::to_string(key.first));
    previousStep = key.first;
    steps.insert(key.first);
  }
  int64_t missingSteps = 0;
  if (!steps.empty()) {
    const int64_t first = (*steps.begin() + stateEvery - 1) / stateEvery * stateEvery;
    for (int64_t s = first; s <= *steps.rbegin(); s += stateEvery)
      if (!steps.count(s)) ++missingSteps;
  }
  if (missingSteps > 0)
    verdict.fail(std::to_string(missingSteps) + " states at multiples of " + std::to_string(stateEvery) +
                 " steps are missing from the record");

  // --- status --------------------------------------------------------------
  if (statuses.empty()) {
    verdict.fail("no status in the record");
  } else {
    const rbsim::status_t& last = statuses.back();
    if (last.commands_accepted + last.commands_rejected != ackEvents)
      verdict.fail("the last status counts " + std::to_string(last.commands_accepted + last.commands_rejected) +
                   " acks; the record holds " + std::to_string(ackEvents));
  }

  // --- figures ---------------------------------------------------------------
  std::printf("SOAK record: %zu events, %.1f MB, parsed %lld of %lld bytes\n", log.events.size(),
              static_cast<double>(log.fileSize) / 1e6, static_cast<long long>(log.bytesParsed),
              static_cast<long long>(log.fileSize));
  std::printf("SOAK messages: sent %lld wrenches + %lld commands by %zu clients; acknowledged exactly once: %lld of %lld "
              "(accepted %lld, rejected %lld)\n",
              static_cast<long long>(sentWrenches), static_cast<long long>(sentCommands), clientPaths.size(),
              static_cast<long long>(accepted + rejected), static_cast<long long>(sentWrenches + sentCommands),
              static_cast<long long>(accepted), static_cast<long long>(rejected));
  std::string kinds;
  for (const auto& [what, count] : commandsByKind) kinds += " " + what + "=" + std::to_string(count);
  std::printf("SOAK commands:%s\n", kinds.c_str());
  for (const std::string& summary : clientSummaries) std::printf("SOAK client %s\n", summary.c_str());
  std::printf("SOAK client-side acks: %lld of %lld received\n", static_cast<long long>(clientAcksReceived),
              static_cast<long long>(clientAcksExpected));
  std::printf("SOAK states: %lld whole in the record (steps %lld..%lld, none missing at multiples of %lld: %s); "
              "%lld received by clients, all in the record\n",
              static_cast<long long>(wholeStates), steps.empty() ? 0LL : static_cast<long long>(*steps.begin()),
              steps.empty() ? 0LL : static_cast<long long>(*steps.rbegin()), static_cast<long long>(stateEvery),
              missingSteps == 0 ? "yes" : "no", static_cast<long long>(clientStates));
  if (!statuses.empty()) {
    const rbsim::status_t& last = statuses.back();
    double worst = 0.0, meanSum = 0.0;
    int meanCount = 0;
    for (const auto& status : statuses) {
      worst = std::max(worst, status.step_time_worst);
      if (status.step_time_mean > 0.0) {
        meanSum += status.step_time_mean;
        ++meanCount;
      }
    }
    std::printf("SOAK server: step %lld, %d bodies (%d frozen), overruns %lld, step time mean %.1f us "
                "(average of %d status windows), worst %.1f us; commands accepted %lld, rejected %lld\n",
                static_cast<long long>(last.step), last.num_bodies, last.num_frozen_bodies,
                static_cast<long long>(last.overruns), meanCount > 0 ? 1e6 * meanSum / meanCount : 0.0, meanCount,
                1e6 * worst, static_cast<long long>(last.commands_accepted),
                static_cast<long long>(last.commands_rejected));
  }
  std::printf("SOAK verdict: %s (%d failures)\n", verdict.failures() == 0 ? "PASS" : "FAIL", verdict.failures());
  return verdict.failures() == 0 ? 0 : 1;
}
