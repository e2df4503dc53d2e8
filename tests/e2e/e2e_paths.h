#pragma once
// What the end-to-end tests run and read, from the build (CMakeLists.txt
// passes them as compile definitions).

namespace rbsim::e2e {

inline constexpr const char* kRbserver = RBSIM_E2E_RBSERVER;
inline constexpr const char* kRbctl = RBSIM_E2E_RBCTL;
inline constexpr const char* kPdExample = RBSIM_E2E_PD_EXAMPLE;
inline constexpr const char* kSpyLauncher = RBSIM_E2E_SPY_LAUNCHER;
inline constexpr const char* kTypesJar = RBSIM_E2E_TYPES_JAR;  // "" without a JDK
inline constexpr const char* kJarTool = RBSIM_E2E_JAR_TOOL;    // "" without a JDK
inline constexpr const char* kWorldsDir = RBSIM_E2E_WORLDS_DIR;
inline constexpr const char* kDefaultWorld = RBSIM_E2E_DEFAULT_WORLD;  // config/default.yaml
inline constexpr const char* kLcmTypesDir = RBSIM_E2E_LCMTYPES_DIR;

// Every process of a test talks on this bus, named explicitly so that an
// LCM_DEFAULT_URL in the environment cannot split server and clients. Each
// test runs in its own network namespace (tests/tools/in_private_network.sh),
// so the same URL never meets another test's traffic.
inline constexpr const char* kUrl = "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152";

}  // namespace rbsim::e2e
