#include "e2e_paths.h"

namespace rbsim::e2e {

const char* const kRbserver = RBSIM_E2E_RBSERVER;
const char* const kRbctl = RBSIM_E2E_RBCTL;
const char* const kPdExample = RBSIM_E2E_PD_EXAMPLE;
const char* const kComputedTorqueExample = RBSIM_E2E_COMPUTED_TORQUE_EXAMPLE;
const char* const kSpyLauncher = RBSIM_E2E_SPY_LAUNCHER;
const char* const kTypesJar = RBSIM_E2E_TYPES_JAR;
const char* const kJarTool = RBSIM_E2E_JAR_TOOL;
const char* const kWorldsDir = RBSIM_E2E_WORLDS_DIR;
const char* const kConfigWorldsDir = RBSIM_E2E_CONFIG_WORLDS_DIR;
const char* const kDefaultWorld = RBSIM_E2E_DEFAULT_WORLD;
const char* const kLcmTypesDir = RBSIM_E2E_LCMTYPES_DIR;
const char* const kTestDataDir = RBSIM_E2E_TEST_DATA_DIR;

}  // namespace rbsim::e2e
