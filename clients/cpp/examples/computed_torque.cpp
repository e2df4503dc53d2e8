// computed_torque: lock-step computed-torque control of a robot (config/worlds/robot_arm.yaml's
// "arm"), one command and one state per step: every joint tracks q0 + 0.3 sin(2π 0.5 t) rad with
// τ = M (q̈_d + Kp e + Kd ė) + h, from the M and h the server sends with each state, as efforts
// (which turn the world file's drives off). The arm starts at rest, the reference at 0.94 rad/s:
// the error of the first --settle s is that catch-up, the tracking error is the largest after it.
// Exit 0 when it is below --tolerance.  computed_torque [--url URL] [--prefix P] [--robot NAME]
//   [--duration S] [--frequency HZ (of the error's dynamics)] [--settle S] [--tolerance RAD]
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "rbsim/client/robot.h"

int main(int argc, char** argv) {
  rbsim::client::ClientOptions options;
  std::string robot = "arm";
  double duration = 2.0, frequency = 20.0, settle = 0.1, tolerance = 1e-3;  // s, Hz, s, rad
  for (int i = 1; i < argc; i += 2) {
    const std::string flag = argv[i], value = i + 1 < argc ? argv[i + 1] : "";
    if (flag == "--url") options.url = value;
    else if (flag == "--prefix") options.channelPrefix = value;
    else if (flag == "--robot") robot = value;
    else if (flag == "--duration") duration = std::stod(value);
    else if (flag == "--frequency") frequency = std::stod(value);
    else if (flag == "--settle") settle = std::stod(value);
    else if (flag == "--tolerance") tolerance = std::stod(value);
    else return std::fprintf(stderr, "usage: computed_torque [--url URL] [--prefix P] [--robot NAME] "
                                     "[--duration S] [--frequency HZ] [--settle S] [--tolerance RAD]\n"), 2;
  }
  rbsim::client::Robot arm(robot, options);
  arm.setDynamics(true);  // sent with the first step: M and h in every state from then on
  if (!arm.waitForState(std::chrono::seconds(5)) || !arm.pause() || !arm.stepSync() || !arm.hasDynamics())
    return std::fprintf(stderr, "computed_torque: %s\n", arm.lastError().c_str()), 3;
  const int n = arm.numJoints();
  const Eigen::VectorXd q0 = arm.q(), zero = Eigen::VectorXd::Zero(n);
  const double t0 = arm.simTime(), w = 2 * std::numbers::pi * 0.5, a = 0.3;     // rad/s, rad
  const double kp = std::pow(2 * std::numbers::pi * frequency, 2), kd = 2 * std::sqrt(kp);  // ζ = 1
  double worst = 0.0, settling = 0.0;
  for (double t = 0.0; t <= duration + 1e-9; t = arm.simTime() - t0) {
    const Eigen::VectorXd qd = q0.array() + a * std::sin(w * t);
    const Eigen::VectorXd qdDot = Eigen::VectorXd::Constant(n, a * w * std::cos(w * t));
    const Eigen::VectorXd qdDdot = Eigen::VectorXd::Constant(n, -a * w * w * std::sin(w * t));
    const Eigen::VectorXd e = qd - arm.q(), eDot = qdDot - arm.qd();
    (t < settle ? settling : worst) = std::max(t < settle ? settling : worst, e.cwiseAbs().maxCoeff());
    if (t + 1e-9 >= duration) break;
    const Eigen::VectorXd tau = arm.massMatrix() * (qdDdot + kp * e + kd * eDot) + arm.bias();
    if (!arm.command(zero, zero, tau, zero, zero) || !arm.stepSync())
      return std::fprintf(stderr, "computed_torque: %s\n", arm.lastError().c_str()), 3;
  }
  std::printf("max tracking error %.3g rad from %.3g s to %.3g s (%.3g rad before), %d joints, step %lld\n",
              worst, settle, duration, settling, n, static_cast<long long>(arm.step()));
  return worst < tolerance ? 0 : 1;
}
