#pragma once
// The folders the robot benchmark reads, from the build. Defined in
// bench_paths.cpp, the one file compiled with the absolute paths, so that
// the benchmark's sources compile to the same objects in any clone (the
// compiler cache shares them).

namespace rbsim::bench {

extern const char* const kRobotsDir;       // config/robots
extern const char* const kWorldsDir;       // config/worlds
extern const char* const kBenchRobotsDir;  // bench/robots

}  // namespace rbsim::bench
