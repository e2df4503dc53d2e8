// The real-time schedule: absolute deadlines, and both catch-up policies.
#include <gtest/gtest.h>

#include "daemon/step_clock.h"

namespace rbsim {
namespace {

constexpr Nanoseconds kMs = 1000000;

TEST(StepClock, DeadlinesAreAbsoluteMultiplesOfThePeriod) {
  StepClock clock(0.001, 1.0, CatchUpPolicy::Burst, 5);
  clock.anchor(10 * kMs);
  for (int k = 0; k < 1000; ++k) {
    const Nanoseconds due = clock.nextDeadline(0);
    EXPECT_EQ(due, 10 * kMs + k * kMs);
    // Starting a little late never shifts later deadlines (no drift).
    EXPECT_EQ(clock.beginStep(due + 30000), 30000);
    clock.endStep(due + 100000);
  }
  EXPECT_EQ(clock.overruns(), 0);
  EXPECT_EQ(clock.slips(), 0);
}

TEST(StepClock, RealTimeFactorScalesThePeriod) {
  StepClock clock(0.001, 2.0, CatchUpPolicy::Burst, 5);
  clock.anchor(0);
  clock.beginStep(0);
  EXPECT_EQ(clock.nextDeadline(0), kMs / 2);
  clock.setRealTimeFactor(0.5, 7 * kMs);
  EXPECT_EQ(clock.nextDeadline(0), 7 * kMs);
  clock.beginStep(7 * kMs);
  EXPECT_EQ(clock.nextDeadline(0), 9 * kMs);
}

TEST(StepClock, UnpacedClockIsAlwaysDue) {
  StepClock clock(0.001, 0.0, CatchUpPolicy::Burst, 5);
  clock.anchor(0);
  EXPECT_EQ(clock.nextDeadline(123), 123);
  EXPECT_EQ(clock.beginStep(5 * kMs), 0);
  clock.endStep(100 * kMs);
  EXPECT_EQ(clock.overruns(), 0);
}

TEST(StepClock, BurstPolicyCatchesUpWithinTheBurstLimit) {
  StepClock clock(0.001, 1.0, CatchUpPolicy::Burst, 5);
  clock.anchor(0);
  clock.beginStep(0);
  clock.endStep(3500000);  // the step took 3.5 ms: overran the next deadline
  EXPECT_EQ(clock.overruns(), 1);
  // 3 steps behind: the schedule keeps its anchor and the next steps are due at once.
  EXPECT_EQ(clock.nextDeadline(0), 1 * kMs);
  EXPECT_EQ(clock.beginStep(3500000), 2500000);
  EXPECT_EQ(clock.nextDeadline(0), 2 * kMs);
  EXPECT_EQ(clock.slips(), 0);
}

TEST(StepClock, BurstPolicyReanchorsBeyondTheBurstLimit) {
  StepClock clock(0.001, 1.0, CatchUpPolicy::Burst, 5);
  clock.anchor(0);
  clock.beginStep(0);
  clock.endStep(20 * kMs);
  clock.beginStep(20 * kMs);  // 19 steps behind > 5: give the time up
  EXPECT_EQ(clock.slips(), 1);
  EXPECT_EQ(clock.nextDeadline(0), 21 * kMs);
}

TEST(StepClock, ReanchorPolicyNeverBursts) {
  StepClock clock(0.001, 1.0, CatchUpPolicy::Reanchor, 5);
  clock.anchor(0);
  clock.beginStep(0);
  clock.beginStep(3 * kMs);  // late by 2 periods: re-anchored at its start
  EXPECT_EQ(clock.nextDeadline(0), 4 * kMs);
  // Less than a period late does not re-anchor.
  clock.beginStep(4 * kMs + 200000);
  EXPECT_EQ(clock.nextDeadline(0), 5 * kMs);
}

}  // namespace
}  // namespace rbsim

#include "daemon/lateness_histogram.h"

namespace rbsim {
namespace {

TEST(LatenessHistogram, PercentilesByNearestRankNeverAboveTheMaximum) {
  LatenessHistogram histogram;
  for (int i = 1; i <= 100; ++i) histogram.add(i * 1000 - 500);  // 0.5 µs, 1.5 µs, ... 99.5 µs
  EXPECT_EQ(histogram.count(), 100);
  EXPECT_EQ(histogram.percentile(0.5), 50000);   // the 50th sample lies in the bin [49, 50) µs
  EXPECT_EQ(histogram.percentile(0.99), 99000);
  EXPECT_EQ(histogram.maximum(), 99500);
  LatenessHistogram small;
  small.add(1512);
  EXPECT_EQ(small.percentile(0.5), 1512);  // capped at the only sample, not its bin edge (2 µs)
}

}  // namespace
}  // namespace rbsim
