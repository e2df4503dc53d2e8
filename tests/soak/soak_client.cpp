// A load client of the soak test, on the C++ client library: for a given
// time it sends a wrench every tick (1 kHz by default) on a random body and
// now and then a random control command, all drawn from a seeded generator.
// Everything it sent, every ack of its own it received and every complete
// state it received goes to a log that soak_check compares with the
// server's record (format in soak_check.cpp). soak_client.py is the Python
// twin; tests/soak/README.md has the whole test.
//
//   soak_client --id ID --seed N --seconds S --log FILE [--rate HZ]
//               [--bodies N] [--command-interval TICKS]
//
// Commands (about one every --command-interval ticks): PAUSE, then a few
// ticks later STEP n and RESUME from this client (the server is never left
// paused for long); SPAWN of a sphere, a box or the tetra mesh in this
// client's own spawn area (now and then with an absolute mesh path, which
// the server must refuse); REMOVE of one of its spawned bodies (or of a name
// that does not exist); PUBLISH_WORLD.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "rbsim/client/client.h"

namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

struct Options {
  std::string id;
  uint64_t seed = 1;
  double seconds = 10.0;
  double rate = 1000.0;  // Hz, wrenches
  int bodies = 500;
  double commandInterval = 1500.0;  // ticks
  std::string logPath;
  int spawnArea = 0;  // which strip of the spawn area is this client's
};

bool parse(int argc, char** argv, Options& options) {
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i];
    const std::string value = argv[i + 1];
    if (key == "--id") options.id = value;
    else if (key == "--seed") options.seed = std::stoull(value);
    else if (key == "--seconds") options.seconds = std::stod(value);
    else if (key == "--rate") options.rate = std::stod(value);
    else if (key == "--bodies") options.bodies = std::stoi(value);
    else if (key == "--command-interval") options.commandInterval = std::stod(value);
    else if (key == "--log") options.logPath = value;
    else if (key == "--spawn-area") options.spawnArea = std::stoi(value);
    else return false;
  }
  return !options.id.empty() && !options.logPath.empty() && argc % 2 == 1;
}

// The client's side of the story, for soak_check.
struct Journal {
  std::vector<std::string> lines;
  void sent(rbsim::client::AckKind kind, int64_t seq, const std::string& what) {
    lines.push_back(std::string("sent ") + (kind == rbsim::client::AckKind::Wrench ? "W " : "C ") +
                    std::to_string(seq) + " " + what);
  }
};

class LoadClient {
 public:
  explicit LoadClient(const Options& options)
      : m_options(options),
        m_client(rbsim::client::ClientOptions{"", "RBSIM_", options.id}),
        m_random(options.seed) {
    m_client.onAck([this](const rbsim::ack_t& ack) {
      if (ack.client != m_options.id) return;
      m_journal.lines.push_back(std::string("ack ") + (ack.kind == rbsim::ack_t::KIND_WRENCH ? "W " : "C ") +
                                std::to_string(ack.seq) + " " + (ack.accepted ? "1" : "0"));
    });
    m_client.onState([this](const rbsim::world_state_t& state) {
      m_journal.lines.push_back("state " + std::to_string(state.step) + " " + std::to_string(state.utime));
    });
  }

  bool good() const { return m_client.good(); }

  void run() {
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / m_options.rate));
    const int64_t ticks = static_cast<int64_t>(m_options.seconds * m_options.rate);
    std::exponential_distribution<double> commandGap(1.0 / m_options.commandInterval);
    int64_t nextCommand = static_cast<int64_t>(commandGap(m_random));
    const Clock::time_point start = Clock::now();
    for (int64_t tick = 0; tick < ticks; ++tick) {
      // Absolute deadlines: a late tick is caught up, so the rate holds on average.
      std::this_thread::sleep_until(start + tick * period);
      m_client.handle(0ms);
      sendWrench();
      if (tick >= nextCommand) {
        sendCommand(tick);
        nextCommand = tick + 1 + static_cast<int64_t>(commandGap(m_random));
      }
      runFollowUps(tick);
    }
    // Leave the server running, then take the last acks in.
    send(m_client.resume(), "resume");
    m_client.spinUntil([] { return false; }, 1500ms);
  }

  bool writeLog() const {
    std::ofstream out(m_options.logPath);
    out << "client " << m_options.id << "\n";
    for (const std::string& line : m_journal.lines) out << line << "\n";
    return static_cast<bool>(out);
  }

 private:
  double uniform(double low, double high) { return std::uniform_real_distribution<double>(low, high)(m_random); }
  int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(m_random); }

  void send(const rbsim::client::Request& request, const std::string& what) {
    if (request.sent) m_journal.sent(request.kind, request.seq, what);
  }

  std::string randomBody() {
    if (!m_spawned.empty() && below(20) == 0) return m_spawned[static_cast<std::size_t>(below(static_cast<int>(m_spawned.size())))];
    return "body" + std::to_string(below(m_options.bodies));
  }

  void sendWrench() {
    rbsim::client::Wrench wrench;
    wrench.body = randomBody();
    const int mode = below(100);
    // Small pushes: the bodies drift a little and now and then touch.
    wrench.force = {uniform(-8, 8), uniform(-8, 8), uniform(-8, 8)};
    wrench.torque = {uniform(-0.5, 0.5), uniform(-0.5, 0.5), uniform(-0.5, 0.5)};
    wrench.frame = below(2) == 0 ? rbsim::client::Frame::Body : rbsim::client::Frame::World;
    if (wrench.frame == rbsim::client::Frame::World) {
      // A world point near the body when the latest state knows it; else
      // the origin, which the lever-arm limit may refuse (an ack all the same).
      wrench.point = {0.0, 0.0, 0.0};
      if (const auto& state = m_client.latestState()) {
        for (const auto& body : state->bodies)
          if (body.name == wrench.body) {
            wrench.point = {body.position[0], body.position[1], body.position[2]};
            break;
          }
      }
    }
    if (mode < 90) {
      wrench.mode = rbsim::client::WrenchMode::OneStep;
    } else if (mode < 95) {
      wrench.mode = rbsim::client::WrenchMode::Duration;
      wrench.duration = uniform(0.01, 0.2);
    } else if (mode < 98) {
      // Through the centre of mass in the body frame: a persistent force at a
      // fixed world point would turn ever faster as the body drifts off it.
      wrench.mode = rbsim::client::WrenchMode::Persistent;
      wrench.frame = rbsim::client::Frame::Body;
      wrench.point = {0.0, 0.0, 0.0};
      wrench.force = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
      wrench.torque = {uniform(-0.2, 0.2), uniform(-0.2, 0.2), uniform(-0.2, 0.2)};
    } else {
      wrench.mode = rbsim::client::WrenchMode::Clear;
    }
    send(m_client.applyWrench(wrench), "wrench");
  }

  void sendCommand(int64_t tick) {
    const int pick = below(100);
    if (pick < 30) {
      send(m_client.pause(), "pause");
      // STEP and RESUME a few ticks later, so the pause is short.
      m_followUps.push_back({tick + 5 + below(60), FollowUp::Step});
      m_followUps.push_back({tick + 80 + below(120), FollowUp::Resume});
    } else if (pick < 60) {
      spawn();
    } else if (pick < 85) {
      if (!m_spawned.empty() && below(5) != 0) {
        const std::size_t which = static_cast<std::size_t>(below(static_cast<int>(m_spawned.size())));
        send(m_client.remove(m_spawned[which]), "remove");
        m_spawned.erase(m_spawned.begin() + static_cast<std::ptrdiff_t>(which));
      } else {
        send(m_client.remove(m_options.id + "-nobody"), "remove-unknown");
      }
    } else {
      send(m_client.publishWorld(), "publish_world");
    }
  }

  void spawn() {
    const std::string name = m_options.id + "-s" + std::to_string(m_spawnCount++);
    // Each client has a strip of its own beyond the grid, so spawned bodies
    // never land inside one another.
    const double x = 40.0 + 10.0 * m_options.spawnArea + uniform(0.0, 8.0);
    const double y = uniform(-20.0, 20.0);
    const int kind = below(10);
    std::string shape;
    if (kind < 4) shape = "{type: sphere, radius: 0.1}";
    else if (kind < 8) shape = "{type: box, half_extents: [0.1, 0.1, 0.1]}";
    else if (kind < 9) shape = "{type: mesh, file: meshes/tetra.obj}";
    else shape = "{type: mesh, file: /etc/rbsim/meshes/tetra.obj}";  // refused: absolute
    const std::string yaml = "{name: " + name + ", shape: " + shape + ", position: [" + std::to_string(x) +
                             ", " + std::to_string(y) + ", 0.5]}";
    send(m_client.spawn(yaml), "spawn");
    if (kind < 9) m_spawned.push_back(name);  // may still be refused; REMOVE is acked either way
    if (m_spawned.size() > 8) {
      send(m_client.remove(m_spawned.front()), "remove");
      m_spawned.erase(m_spawned.begin());
    }
  }

  struct FollowUp {
    enum Kind { Step, Resume };
    int64_t tick;
    Kind kind;
  };

  void runFollowUps(int64_t tick) {
    while (true) {
      const auto due = std::find_if(m_followUps.begin(), m_followUps.end(),
                                    [tick](const FollowUp& f) { return f.tick <= tick; });
      if (due == m_followUps.end()) return;
      const FollowUp followUp = *due;
      m_followUps.erase(due);
      if (followUp.kind == FollowUp::Step) send(m_client.step(1 + below(20)), "step");
      else send(m_client.resume(), "resume");
    }
  }

  Options m_options;
  rbsim::client::Client m_client;
  std::mt19937_64 m_random;
  Journal m_journal;
  std::vector<std::string> m_spawned;
  std::deque<FollowUp> m_followUps;
  int m_spawnCount = 0;
};

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parse(argc, argv, options)) {
    std::fprintf(stderr,
                 "usage: soak_client --id ID --seed N --seconds S --log FILE [--rate HZ] [--bodies N]"
                 " [--command-interval TICKS] [--spawn-area K]\n");
    return 2;
  }
  LoadClient client(options);
  if (!client.good()) {
    std::fprintf(stderr, "soak_client %s: cannot open LCM\n", options.id.c_str());
    return 1;
  }
  client.run();
  if (!client.writeLog()) {
    std::fprintf(stderr, "soak_client %s: cannot write %s\n", options.id.c_str(), options.logPath.c_str());
    return 1;
  }
  return 0;
}
