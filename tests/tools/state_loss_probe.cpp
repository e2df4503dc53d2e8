// Counts complete world states received on RBSIM_STATE (all pages of a step)
// and reports steps with missing pages: the check that a large world reaches
// clients without loss. Exits 0 when at least --expect complete states arrived
// and none was incomplete.
//
//   state_loss_probe --seconds S --expect N [--url URL] [--prefix P]
#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include <rbsim/world_state_t.hpp>

namespace {

struct Counter {
  std::map<int64_t, std::set<int32_t>> pagesByStep;
  std::map<int64_t, int32_t> expectedPages;
  int64_t bodiesSeen = 0;

  void onState(const lcm::ReceiveBuffer*, const std::string&, const rbsim::world_state_t* state) {
    pagesByStep[state->step].insert(state->page);
    expectedPages[state->step] = state->num_pages;
    bodiesSeen += state->num_bodies;
  }
};

}  // namespace

int main(int argc, char** argv) {
  std::string url = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152", prefix = "RBSIM_";
  double seconds = 3.0;
  long expect = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string arg = argv[i];
    if (arg == "--seconds") seconds = std::stod(argv[i + 1]);
    else if (arg == "--expect") expect = std::stol(argv[i + 1]);
    else if (arg == "--url") url = argv[i + 1];
    else if (arg == "--prefix") prefix = argv[i + 1];
    else {
      std::fprintf(stderr, "state_loss_probe: unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  lcm::LCM lcm(url);
  if (!lcm.good()) return 1;
  Counter counter;
  lcm.subscribe(prefix + "STATE", &Counter::onState, &counter)->setQueueCapacity(100000);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                          std::chrono::duration<double>(seconds));
  while (std::chrono::steady_clock::now() < end) lcm.handleTimeout(20);

  // The first and last step seen may be cut by the start and end of the
  // listening window; every step between them must be whole, and no step in
  // the regular stride of published steps may be missing altogether.
  long complete = 0, incomplete = 0, missing = 0;
  int64_t stride = 0, previous = -1;
  for (const auto& entry : counter.pagesByStep) {
    if (previous >= 0 && (stride == 0 || entry.first - previous < stride)) stride = entry.first - previous;
    previous = entry.first;
  }
  previous = -1;
  const int64_t first = counter.pagesByStep.empty() ? 0 : counter.pagesByStep.begin()->first;
  const int64_t last = counter.pagesByStep.empty() ? 0 : counter.pagesByStep.rbegin()->first;
  for (const auto& [step, pages] : counter.pagesByStep) {
    const bool whole = static_cast<int32_t>(pages.size()) == counter.expectedPages[step];
    if (whole) ++complete;
    else if (step != first && step != last) ++incomplete;
    if (previous >= 0 && stride > 0) missing += (step - previous) / stride - 1;
    previous = step;
  }
  const int pagesPerState = counter.expectedPages.empty() ? 0 : counter.expectedPages.begin()->second;
  std::printf("state_loss_probe: %ld complete states (%d pages each, every %lld steps), %ld incomplete, "
              "%ld missing, %lld body states\n",
              complete, pagesPerState, static_cast<long long>(stride), incomplete, missing,
              static_cast<long long>(counter.bodiesSeen));
  return complete >= expect && incomplete == 0 && missing == 0 ? 0 : 1;
}
