#pragma once
// What the end-to-end tests run and read, from the build. Defined in
// e2e_paths.cpp, the one file that CMakeLists.txt compiles with the absolute
// paths, so that the test sources compile to the same objects in any clone
// (the compiler cache shares them; CI builds a fresh clone).

namespace rbsim::e2e {

extern const char* const kRbserver;
extern const char* const kRbctl;
extern const char* const kPdExample;
extern const char* const kComputedTorqueExample;
extern const char* const kSpyLauncher;
extern const char* const kTypesJar;  // "" without a JDK
extern const char* const kJarTool;   // "" without a JDK
extern const char* const kWorldsDir;        // tests/e2e/worlds
extern const char* const kConfigWorldsDir;  // config/worlds
extern const char* const kDefaultWorld;     // config/default.yaml
extern const char* const kLcmTypesDir;
extern const char* const kTestDataDir;      // tests/data

// Every process of a test talks on this bus, named explicitly so that an
// LCM_DEFAULT_URL in the environment cannot split server and clients. Each
// test runs in its own network namespace (tests/tools/in_private_network.sh),
// so the same URL never meets another test's traffic.
inline constexpr const char* kUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152";

}  // namespace rbsim::e2e
