#pragma once
// How many threads share a world's step (WorldSettings::threads). Every
// count gives the same bits; the count only changes how fast a step is.

namespace rbsim {

// The most threads a world takes (config and --threads are checked against it).
inline constexpr int kMaxThreads = 256;

// The number of threads `threads` asks for: itself when positive, else the
// cores this process may run on (at least 1).
int resolveThreadCount(int threads);

}  // namespace rbsim
