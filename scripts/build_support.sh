# Sourced by the scripts that build (run_tests.sh, quick_test.sh,
# tests/fuzz/run_fuzzers.sh).

# configure DIR CMAKE_ARGS...: cmake -S . -B DIR with Ninja for a new build
# directory (when ninja is installed); an existing one keeps the generator
# it was made with, as CMake requires.
configure() {
  local dir=$1
  shift
  local generator=()
  if [ ! -f "$dir/CMakeCache.txt" ] && command -v ninja >/dev/null 2>&1; then
    generator=(-G Ninja)
  fi
  cmake -S . -B "$dir" "${generator[@]}" "$@"
}
