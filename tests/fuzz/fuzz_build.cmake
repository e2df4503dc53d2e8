# Compiler settings of the libFuzzer build (RBSIM_FUZZ=ON), included from the
# top-level CMakeLists.txt before any target is defined, so that every
# library the fuzz targets link is instrumented the same way.

if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang" OR NOT CMAKE_C_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR
    "RBSIM_FUZZ=ON needs clang (libFuzzer): configure a separate build directory with "
    "CC=clang CXX=clang++ cmake -S . -B build-fuzz -DRBSIM_FUZZ=ON "
    "(Debian: apt-get install clang libclang-rt-14-dev)")
endif()

# Optimised, but with assertions on: an assert that input can reach is a bug
# the fuzzers must see. -O2 rather than the usual -O1: at -O1 Eigen's
# fixed-size loops stay loops, every bound check gets a comparison hook, and
# a step of a small world in contact runs about 5x slower. Line tables are
# enough for the stack traces and cheaper to build than full debug info.
set(CMAKE_BUILD_TYPE RelWithDebInfo CACHE STRING "Build type" FORCE)
set(CMAKE_C_FLAGS_RELWITHDEBINFO "-O2 -gline-tables-only" CACHE STRING "" FORCE)
set(CMAKE_CXX_FLAGS_RELWITHDEBINFO "-O2 -gline-tables-only" CACHE STRING "" FORCE)

# Libraries get coverage instrumentation without libFuzzer's main(); the fuzz
# targets link -fsanitize=fuzzer (tests/fuzz/CMakeLists.txt). Every UBSan
# finding aborts (no recovery), so that libFuzzer records it as a crash.
# float-divide-by-zero is not in `undefined`: IEEE division by zero is
# defined, and the engine relies on it giving inf.
set(RBSIM_SANITIZERS address,undefined)
add_compile_options(-fsanitize=fuzzer-no-link,${RBSIM_SANITIZERS}
                    -fno-sanitize-recover=all -fno-omit-frame-pointer)
add_link_options(-fsanitize=${RBSIM_SANITIZERS})
