#pragma once
// Whether this is a ThreadSanitizer build (clang's test, and GCC's macro):
// the task pool then offers every loop to its workers (task_pool.h), and
// tests that hold a worker with a signal, which ThreadSanitizer may defer,
// are skipped.

namespace rbsim {

#if defined(__SANITIZE_THREAD__)
inline constexpr bool kThreadSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
inline constexpr bool kThreadSanitizer = true;
#else
inline constexpr bool kThreadSanitizer = false;
#endif
#else
inline constexpr bool kThreadSanitizer = false;
#endif

}  // namespace rbsim
