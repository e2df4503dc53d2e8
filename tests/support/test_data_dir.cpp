#include "support/test_data_dir.h"

namespace rbsim::test_support {

const char* const kTestDataDir = RBSIM_TEST_DATA_DIR;

}  // namespace rbsim::test_support
