#include "physics/joint/axis_actuation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace rbsim {

namespace {

// L(w) = alpha + beta w, as it is on an open interval between breakpoints.
struct Affine {
  double alpha = 0.0;
  double beta = 0.0;
  double at(double w) const { return alpha + beta * w; }
};

// The drive's impulse before its cap, −h (k (e + s w) + c (w − v)), as an
// affine function of w.
Affine uncappedDrive(const AxisLaw& law) {
  Affine drive{-law.h * law.driveStiffness * law.driveError,
               -law.h * (law.driveStiffness * law.driveLookahead + law.driveDamping)};
  // Only when there is one, so that a drive without a target rate keeps
  // the bits it had before target rates were.
  if (law.driveTargetRate != 0.0) drive.alpha += law.h * law.driveDamping * law.driveTargetRate;
  return drive;
}

// The drive's impulse at rate w: capped, and none that pushes faster than
// its rate limit (at exactly ±R, the value just inside it).
double driveAt(const AxisLaw& law, double w) {
  const double value = std::clamp(uncappedDrive(law).at(w), -law.driveCap, law.driveCap);
  if (w > law.driveRateLimit) return std::min(value, 0.0);
  if (w < -law.driveRateLimit) return std::max(value, 0.0);
  return value;
}

// Each law on the open interval that holds `w` (a point that is no
// breakpoint). `actuation` is the motor's and drive's part alone.
Affine lawsNear(const AxisLaw& law, double w, bool actuationOnly = false) {
  Affine sum;
  if (law.motor) sum.alpha += w < law.motorTarget ? law.motorCap : -law.motorCap;
  if (law.drive) {
    const Affine raw = uncappedDrive(law);
    const double value = raw.at(w);
    const bool stopped = (w > law.driveRateLimit && value > 0.0) || (w < -law.driveRateLimit && value < 0.0);
    if (stopped) {
      // beyond the rate limit, pushing on: nothing
    } else if (value > law.driveCap) {
      sum.alpha += law.driveCap;
    } else if (value < -law.driveCap) {
      sum.alpha -= law.driveCap;
    } else {
      sum.alpha += raw.alpha;
      sum.beta += raw.beta;
    }
  }
  if (actuationOnly) return sum;
  if (law.frictionCap > 0.0) sum.alpha += w < 0.0 ? law.frictionCap : -law.frictionCap;
  sum.beta -= law.h * law.damping;
  return sum;
}

}  // namespace

AxisImpulse solveAxisLaw(const AxisLaw& law, double freeRate, double inverseMass) {
  // The rates where L jumps (the motor's target, friction's zero, the
  // drive's rate limits) or bends (where the drive reaches its cap or
  // changes sign), ascending.
  std::array<double, 7> breaks{};
  int count = 0;
  if (law.motor) breaks[count++] = law.motorTarget;
  if (law.frictionCap > 0.0) breaks[count++] = 0.0;
  const bool rateLimited = law.drive && std::isfinite(law.driveRateLimit);
  if (law.drive) {
    const Affine raw = uncappedDrive(law);
    if (std::isfinite(law.driveCap) && raw.beta < 0.0) {
      breaks[count++] = (law.driveCap - raw.alpha) / raw.beta;
      breaks[count++] = (-law.driveCap - raw.alpha) / raw.beta;
    }
    if (rateLimited) {
      breaks[count++] = -law.driveRateLimit;
      breaks[count++] = law.driveRateLimit;
      if (raw.beta < 0.0) breaks[count++] = -raw.alpha / raw.beta;
    }
  }
  // Ascending, each once (insertion: at most four).
  for (int i = 1; i < count; ++i)
    for (int j = i; j > 0 && breaks[static_cast<std::size_t>(j)] < breaks[static_cast<std::size_t>(j - 1)]; --j)
      std::swap(breaks[static_cast<std::size_t>(j)], breaks[static_cast<std::size_t>(j - 1)]);
  int unique = 0;
  for (int i = 0; i < count; ++i)
    if (unique == 0 || breaks[static_cast<std::size_t>(i)] != breaks[static_cast<std::size_t>(unique - 1)])
      breaks[static_cast<std::size_t>(unique++)] = breaks[static_cast<std::size_t>(i)];
  count = unique;

  // g(w) = (w − w_free)/a − L(w) increases strictly; its root is the end rate.
  // A point inside segment s (s = 0 before the first breakpoint, s = count
  // after the last).
  const auto inside = [&](int s) {
    if (count == 0) return 0.0;
    if (s == 0) return breaks[0] - 1.0 - std::abs(breaks[0]);
    if (s == count) return breaks[count - 1] + 1.0 + std::abs(breaks[count - 1]);
    return 0.5 * (breaks[s - 1] + breaks[s]);
  };
  const auto g = [&](double w, const Affine& l) { return (w - freeRate) / inverseMass - l.at(w); };
  AxisImpulse out;
  const auto rootIn = [&](int s) {
    const Affine l = lawsNear(law, inside(s));
    out.rate = (freeRate / inverseMass + l.alpha) / (1.0 / inverseMass - l.beta);
    out.total = l.at(out.rate);
    out.actuation = lawsNear(law, inside(s), true).at(out.rate);
  };
  for (int j = 0; j < count; ++j) {
    const double b = breaks[j];
    const Affine left = lawsNear(law, inside(j));
    if (g(b, left) > 0.0) {
      rootIn(j);
      return out;
    }
    const Affine right = lawsNear(law, inside(j + 1));
    if (g(b, right) >= 0.0) {
      // The root is the breakpoint itself: a motor at its target, or
      // friction holding. The single-valued laws take their value there;
      // friction holds what it can, and the motor the rest.
      out.rate = b;
      out.total = (b - freeRate) / inverseMass;
      double rest = out.total;
      double actuation = 0.0;
      // At its rate limit the drive holds the rate (with at most what it
      // would give there; a motor, its only rival there, is never on
      // with it).
      const bool driveHere = rateLimited && (b == law.driveRateLimit || b == -law.driveRateLimit);
      if (law.drive && !driveHere) {
        const double drive = driveAt(law, b);
        actuation += drive;
        rest -= drive;
      }
      rest += law.h * law.damping * b;
      const bool motorHere = law.motor && b == law.motorTarget;
      if (law.motor && !motorHere) {
        const double motor = b < law.motorTarget ? law.motorCap : -law.motorCap;
        actuation += motor;
        rest -= motor;
      }
      if (law.frictionCap > 0.0) {
        const double friction = b == 0.0 ? (motorHere ? std::clamp(rest, -law.frictionCap, law.frictionCap) : rest)
                                         : (b < 0.0 ? law.frictionCap : -law.frictionCap);
        rest -= friction;
      }
      if (motorHere || driveHere) actuation += rest;  // the motor (or drive) holds its rate with what is left
      out.actuation = actuation;
      return out;
    }
  }
  rootIn(count);
  return out;
}

double actuationAtRate(const AxisLaw& law, double rate) {
  double actuation = 0.0;
  if (law.motor && rate != law.motorTarget) actuation += rate < law.motorTarget ? law.motorCap : -law.motorCap;
  if (law.drive) actuation += driveAt(law, rate);
  return actuation;
}

}  // namespace rbsim
