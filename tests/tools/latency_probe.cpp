// Wrench-to-ack latency on LCM: publishes one-step wrenches at a fixed rate
// and times each until its ack arrives (steady clock, same process, so no
// clock offset). Prints p50/p99/max and the count of acks never received.
//
//   latency_probe --body NAME [--rate HZ] [--seconds S] [--url URL] [--prefix P]
#include <lcm/lcm-cpp.hpp>
#include <poll.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include <rbsim/ack_t.hpp>
#include <rbsim/wrench_t.hpp>

namespace {

using Clock = std::chrono::steady_clock;

struct Probe {
  std::unordered_map<int64_t, Clock::time_point> sent;
  std::vector<double> latenciesMicroseconds;
  int rejected = 0;
  std::string clientId;

  void onAck(const lcm::ReceiveBuffer*, const std::string&, const rbsim::ack_t* ack) {
    if (ack->client != clientId) return;
    const auto found = sent.find(ack->seq);
    if (found == sent.end()) return;
    latenciesMicroseconds.push_back(
        std::chrono::duration<double, std::micro>(Clock::now() - found->second).count());
    if (!ack->accepted) ++rejected;
    sent.erase(found);
  }
};

double percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::max(1.0, std::ceil(q * static_cast<double>(values.size()))));
  return values[rank - 1];
}

}  // namespace

int main(int argc, char** argv) {
  std::string body, url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152", prefix = "RBSIM_";
  double rate = 100.0, seconds = 10.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string arg = argv[i];
    if (arg == "--body") body = argv[i + 1];
    else if (arg == "--rate") rate = std::stod(argv[i + 1]);
    else if (arg == "--seconds") seconds = std::stod(argv[i + 1]);
    else if (arg == "--url") url = argv[i + 1];
    else if (arg == "--prefix") prefix = argv[i + 1];
    else {
      std::fprintf(stderr, "latency_probe: unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  if (body.empty() || rate <= 0.0 || seconds <= 0.0) {
    std::fprintf(stderr, "usage: latency_probe --body NAME [--rate HZ] [--seconds S] [--url URL]\n");
    return 2;
  }
  lcm::LCM lcm(url);
  if (!lcm.good()) {
    std::fprintf(stderr, "latency_probe: cannot open LCM at %s\n", url.c_str());
    return 1;
  }
  Probe probe;
  probe.clientId = "latency-probe-" + std::to_string(getpid());
  lcm.subscribe(prefix + "ACK", &Probe::onAck, &probe)->setQueueCapacity(10000);

  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate));
  const auto start = Clock::now();
  const auto end = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
  auto next = start;
  int64_t seq = 0;
  rbsim::wrench_t wrench{};
  wrench.client = probe.clientId;
  wrench.body = body;
  wrench.frame = rbsim::wrench_t::FRAME_WORLD;
  wrench.mode = rbsim::wrench_t::MODE_ONE_STEP;
  wrench.apply_at_step = -1;
  wrench.force[2] = 1e-3;  // tiny: the probe measures the path, not the physics
  while (Clock::now() < end) {
    if (Clock::now() >= next) {
      wrench.seq = ++seq;
      wrench.utime = std::chrono::duration_cast<std::chrono::microseconds>(
                         std::chrono::system_clock::now().time_since_epoch()).count();
      probe.sent[seq] = Clock::now();
      lcm.publish(prefix + "WRENCH", &wrench);
      next += period;
    }
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(next - Clock::now()).count();
    pollfd fd{lcm.getFileno(), POLLIN, 0};
    if (poll(&fd, 1, static_cast<int>(std::max<int64_t>(0, wait))) > 0) lcm.handleTimeout(0);
  }
  // Grace period for the last acks.
  const auto grace = Clock::now() + std::chrono::milliseconds(500);
  while (!probe.sent.empty() && Clock::now() < grace) lcm.handleTimeout(50);

  const auto& l = probe.latenciesMicroseconds;
  std::printf("latency_probe: sent %lld, acked %zu, lost %zu, rejected %d; wrench->ack latency p50 %.1f us, p99 %.1f us, max %.1f us\n",
              static_cast<long long>(seq), l.size(), probe.sent.size(), probe.rejected,
              percentile(l, 0.5), percentile(l, 0.99), l.empty() ? 0.0 : *std::max_element(l.begin(), l.end()));
  return probe.sent.empty() && probe.rejected == 0 ? 0 : 1;
}
