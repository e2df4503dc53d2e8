#include "bench_paths.h"

namespace rbsim::bench {

const char* const kRobotsDir = RBSIM_ROBOTS_DIR;
const char* const kWorldsDir = RBSIM_WORLDS_DIR;
const char* const kBenchRobotsDir = RBSIM_BENCH_ROBOTS_DIR;

}  // namespace rbsim::bench
