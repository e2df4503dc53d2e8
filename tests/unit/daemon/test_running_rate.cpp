// The shutdown summary's real-time factor leaves paused time out.
#include <gtest/gtest.h>

#include "daemon/running_rate.h"

namespace rbsim {
namespace {

constexpr Nanoseconds kSecond = 1000000000;

TEST(RunningRate, PausedTimeAndItsStepsAreNotCounted) {
  RunningRate rate;
  rate.mark(0, false);
  for (int i = 0; i < 1000; ++i) rate.stepped();  // 1 s of steps at dt = 1 ms...
  rate.mark(1 * kSecond, true);                   // ...in 1 s of running
  rate.mark(4 * kSecond, false);                  // then paused for 3 s
  for (int i = 0; i < 500; ++i) rate.stepped();
  rate.mark(5 * kSecond, true);  // 0.5 s of steps in 1 s
  EXPECT_DOUBLE_EQ(rate.runningSeconds(), 2.0);
  EXPECT_DOUBLE_EQ(rate.factor(0.001), 0.75);  // not 1.5 s / 5 s = 0.3
}

TEST(RunningRate, NoRunningTimeIsZero) {
  RunningRate rate;
  rate.mark(0, false);
  rate.mark(kSecond, false);
  EXPECT_EQ(rate.factor(0.001), 0.0);
}

}  // namespace
}  // namespace rbsim
