// computed_torque [--url URL] [--robot NAME] [--duration S] [--tolerance RAD]: lock-step control
// of config/worlds/robot_arm.yaml's arm, one command and one state a step; each joint tracks
// q0 + 0.3 sin(2π 0.5 t) rad for 2 s with τ = M (q̈_d + Kp e + Kd ė) + h + b q̇_d + f sign(q̇_d), as
// efforts (the file's drives off); M, h from each state, the joints' damping b and friction f (not
// in h) from world_t. A 0.2 s lead-in eases each joint from rest onto the sine's 0.94 rad/s (a
// jump saturates the joints). Prints the largest error after it, resumes; 0: below --tolerance.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "rbsim/client/robot.h"

int main(int argc, char** argv) {
  rbsim::client::ClientOptions options;
  std::string robot = "arm";
  double duration = 2.0, tolerance = 1e-3;  // s, rad
  for (int i = 1; i + 1 < argc; i += 2) {
    if (const std::string flag = argv[i]; flag == "--url") options.url = argv[i + 1];
    else if (flag == "--robot") robot = argv[i + 1];
    else if (flag == "--duration") duration = std::stod(argv[i + 1]);
    else if (flag == "--tolerance") tolerance = std::stod(argv[i + 1]);
    else return std::fprintf(stderr, "computed_torque: unknown option %s\n", argv[i]), 2;
  }
  rbsim::client::Robot arm(robot, options);
  const auto failed = [&] { return std::fprintf(stderr, "%s\n", arm.lastError().c_str()), 3; };
  if (!arm.waitForState(std::chrono::seconds(5)) || !arm.pause()) return failed();
  const int n = arm.numJoints();
  Eigen::VectorXd b(n), f(n);
  {  // b and f from world_t, then the Client goes: unread, it would queue every state
    rbsim::client::Client sim(options);
    sim.publishWorld();
    if (!sim.spinUntil([&] { return sim.world().has_value(); }, std::chrono::seconds(5))) return 3;
    for (int i = 0; i < n; ++i) b[i] = sim.jointDescription(arm.jointNames()[i])->damping;
    for (int i = 0; i < n; ++i) f[i] = sim.jointDescription(arm.jointNames()[i])->friction;
  }
  arm.setDynamics(true);  // sent with the next step: M and h in every state from then on
  if (!arm.stepSync() || !arm.hasDynamics()) return failed();
  const double a = 0.3, w = std::numbers::pi, v = a * w, lead = 0.2, t0 = arm.simTime() + lead;
  const double kp = std::pow(2 * std::numbers::pi * 20, 2), kd = 2 * std::sqrt(kp);  // 20 Hz, ζ = 1
  const Eigen::VectorXd start = arm.q();
  double worst = 0.0;
  for (double t = -lead;; t = arm.simTime() - t0) {
    const double x = (t + lead) / lead, x2 = x * x;  // r(t): a quartic (rate 0 to v), the sine
    const double r = t < 0 ? v * lead * x2 * x * (1 - x / 2) : v * lead / 2 + a * std::sin(w * t);
    const double rDot = t < 0 ? v * x2 * (3 - 2 * x) : v * std::cos(w * t);
    const double rDdot = t < 0 ? 6 * v * x * (1 - x) / lead : -a * w * w * std::sin(w * t);
    const Eigen::VectorXd e = (start.array() + r - arm.q().array()).matrix();
    const Eigen::VectorXd eDot = (rDot - arm.qd().array()).matrix();
    if (t >= 0) worst = std::max(worst, e.cwiseAbs().maxCoeff());
    if (t >= duration - 1e-9) break;
    const Eigen::VectorXd accel = (rDdot + (kp * e + kd * eDot).array()).matrix();
    const Eigen::VectorXd tau = arm.massMatrix() * accel + arm.bias() + b * rDot +
                                f * static_cast<double>((rDot > 0) - (rDot < 0));
    if (!arm.commandEffort(tau) || !arm.stepSync()) return failed();
  }
  std::printf("max tracking error %.3g rad over %.3g s, %d joints\n", worst, duration, n);
  return arm.resume() ? (worst < tolerance ? 0 : 1) : failed();
}
