#pragma once
// Where the tests' data files are (tests/data), from the build. Defined in
// test_data_dir.cpp, the one file compiled with the folder's absolute path,
// so that the test sources themselves compile to the same objects in any
// clone and the compiler cache shares them.

namespace rbsim::test_support {

extern const char* const kTestDataDir;

}  // namespace rbsim::test_support
