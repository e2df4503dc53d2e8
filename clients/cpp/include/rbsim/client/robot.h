#pragma once
// One robot of a running rbserver, commanded and read whole: a
// robot_command_t for all its joints per control cycle, a robot_state_t per
// step it is published at (its joints, and on request its mass matrix, bias
// forces and link Jacobians). lcmtypes/rbsim/robot_command_t.lcm and
// robot_state_t.lcm have the semantics; docs/robots_and_joints.md the rest.
//
// A Robot opens its own LCM connection and subscribes to <prefix>ROBOT_STATE
// and <prefix>ACK only: a controller's loop then decodes its robot's state
// and its acks and nothing else (not the world's state pages, joints or
// contacts, which a Client decodes, all of them, on every step). It can
// pause and resume the server (their acks come on ACK too); everything else
// stays with a Client, which may run beside it.
//
// Threading as Client: none hidden; messages are received only inside the
// calls that wait (waitForState, stepSync, waitForAck, handle), on the
// calling thread; not thread-safe.
//
// The lock-step loop of a paused server (one message and one state per cycle):
//
//   rbsim::client::Robot arm("arm");
//   if (!arm.waitForState(2s) || !arm.pause()) ...  // joint names, q, q̇; then lock step
//   arm.setDynamics(true);                          // M, h, Jacobians from the next state on
//   while (...) {
//     arm.command(q_d, qd_d, tau_ff, kp, kd);       // per joint; kp = kd = 0: effort alone
//     if (!arm.stepSync()) ... arm.lastError()      // one step, then its state
//     ... arm.q(), arm.qd(), arm.massMatrix(), arm.bias(), arm.jacobian("link7") ...
//   }

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <optional>
#include <rbsim/ack_t.hpp>
#include <rbsim/robot_command_t.hpp>
#include <rbsim/robot_state_t.hpp>
#include <string>
#include <utility>
#include <vector>

#include "rbsim/client/client.h"

namespace rbsim::client {

// A link's frame as robot_state_t gives it (with the dynamics only).
struct LinkPose {
  Eigen::Vector3d position;     // m, world frame
  Eigen::Vector4d orientation;  // (w, x, y, z), world frame
};

class Robot {
 public:
  using Timeout = std::chrono::milliseconds;

  // The robot whose joints are named "<name>/...". Nothing is sent: the
  // first state says which joints it has (waitForState).
  explicit Robot(std::string name, ClientOptions options = {});
  ~Robot();
  // Registered with LCM by address: neither copyable nor movable.
  Robot(const Robot&) = delete;
  Robot& operator=(const Robot&) = delete;

  // False when LCM could not be opened; every wait then fails at once.
  bool good() const;
  const std::string& name() const { return m_name; }
  const std::string& clientId() const { return m_clientId; }
  lcm::LCM& lcm() { return *m_lcm; }

  // Why the last call that returned false (or an empty optional) failed:
  // no answer within the timeout, the server's reason for a refusal, a
  // vector of the wrong size, a link it does not have.
  const std::string& lastError() const { return m_error; }

  // --- receiving -----------------------------------------------------------

  // As Client::handle: waits up to `timeout` for a message, then dispatches
  // it and every other one already waiting; returns how many (−1: LCM error).
  int handle(Timeout timeout);
  // Until a state of this robot has come (with `withDynamics`, one that
  // carries the dynamics or a note saying why it cannot); false after
  // `timeout`.
  bool waitForState(Timeout timeout, bool withDynamics = false);
  // Until a state of step `step` or later has come (the newest one held
  // counts, even from before a RESET).
  bool waitForStep(int64_t step, Timeout timeout);

  // The newest state of this robot (by arrival), if any.
  const std::optional<rbsim::robot_state_t>& state() const { return m_state; }
  uint64_t stateCount() const { return m_stateCount; }
  // The robot's joints (robot_state_t.joint_names: "<robot>/<joint>"), in
  // the order of every vector below and of command(); empty before the
  // first state.
  const std::vector<std::string>& jointNames() const;
  int numJoints() const { return static_cast<int>(jointNames().size()); }
  // The newest state's step and simulated time, s (−1 and NaN before one).
  int64_t step() const;
  double simTime() const;
  // rad or m, rad/s or m/s, and N·m or N (what the actuators applied over
  // the last step), in jointNames() order; empty before the first state.
  Eigen::VectorXd q() const;
  Eigen::VectorXd qd() const;
  Eigen::VectorXd tau() const;

  // The dynamics of the newest state (setDynamics(true); when the server
  // cannot give them, hasDynamics() stays false and dynamicsNote() says
  // why). Their size m is the state's num_dofs: n, the joints, for a fixed
  // base; 6 + n for a floating one, whose first six coordinates are its
  // frame origin's velocity and its angular velocity (world frame).
  bool hasDynamics() const;
  const std::string& dynamicsNote() const;
  Eigen::MatrixXd massMatrix() const;  // M(q), m × m (0 × 0 without the dynamics)
  Eigen::VectorXd bias() const;        // h(q, q̇) = gravity + Coriolis and centrifugal
  Eigen::VectorXd gravity() const;     // g(q)
  // The links (the robot's bodies, merged links as one; a floating base
  // first, a fixed base not at all), parents first.
  const std::vector<std::string>& linkNames() const;
  // `link` by its full name ("arm/link7") or the robot's own ("link7").
  std::optional<LinkPose> linkPose(const std::string& link) const;
  // The 6 × m Jacobian of the link frame's origin, or of `worldPoint` (m,
  // world frame) fixed on the link: rows 0–2 the point's velocity, 3–5 the
  // link's angular velocity, world frame, per velocity coordinate.
  std::optional<Eigen::MatrixXd> jacobian(const std::string& link) const;
  std::optional<Eigen::MatrixXd> jacobian(const std::string& link,
                                          const Eigen::Vector3d& worldPoint) const;

  // --- commanding ----------------------------------------------------------

  // What the next message sent (send() or stepSync()) commands, per joint in
  // jointNames() order: with kp or kd not 0 the joint's position drive
  // pulls it to q with stiffness kp and damping kd, towards the rate qd, plus
  // the feed-forward tau_ff (MODE_POSITION, uncapped); with kp = kd = 0 the
  // effort tau_ff alone (MODE_EFFORT, which turns the drive off). A mimic
  // follower is left to its leader (MODE_KEEP). False (and nothing kept)
  // when a vector's size is not numJoints() or before the first state.
  bool command(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& tauFF,
               const Eigen::VectorXd& kp, const Eigen::VectorXd& kd);
  // MODE_EFFORT on every joint: command(_, _, tau, 0, 0).
  bool commandEffort(const Eigen::VectorXd& tau);
  // Any entries (modes, max_effort; named joints): the next message carries
  // these joint fields of `message` as they are (num_joints, num_names,
  // joint_names, mode, position, velocity, effort, stiffness, damping,
  // max_effort); its other fields are the Robot's.
  void commandRaw(const rbsim::robot_command_t& message);
  // Whether a command is waiting for the next message.
  bool hasPendingCommand() const { return m_hasPending; }

  // Settings the next message carries (then the server keeps them): the
  // robot's state rate, Hz (−1: back to the world state's rate), and whether
  // its states carry the dynamics.
  void setStateRate(double hz) { m_stateRate = hz; }
  void setDynamics(bool on) { m_dynamics = on ? 1 : 0; }

  // Sends the pending command and settings now (none: a message that
  // changes nothing, still acked), to act from `applyAtStep` (−1: the next
  // step), and `steps` steps taken after it if > 0 (the server must be
  // paused). Returns at once; waitForAck(request) has the answer.
  Request send(int64_t applyAtStep = -1, int32_t steps = 0);
  // The lock-step cycle of a paused server: send(-1, steps), its ack, then
  // the state of the last of those steps (step == effective_step + steps − 1),
  // which state() then holds. False on a refusal or no answer within
  // `timeout` (lastError() says which).
  bool stepSync(int32_t steps = 1, Timeout timeout = std::chrono::seconds(2));

  // The ack of the last stepSync()'s command (its effective_step, and its
  // utime: when the server took it), if one came.
  const std::optional<rbsim::ack_t>& lastAck() const { return m_lastAck; }
  // The ack answering this Robot's `request`, handling messages until it is
  // there; nullopt after `timeout`.
  std::optional<rbsim::ack_t> waitForAck(const Request& request, Timeout timeout);
  // Pause and resume the server (command_t on <prefix>COMMAND), waiting for
  // the ack: false when refused or unanswered. A lock-step loop pauses first.
  bool pause(Timeout timeout = std::chrono::seconds(2));
  bool resume(Timeout timeout = std::chrono::seconds(2));

 private:
  void onState(const lcm::ReceiveBuffer*, const std::string&, const rbsim::robot_state_t* state);
  void onAck(const lcm::ReceiveBuffer*, const std::string&, const rbsim::ack_t* ack);
  bool spinUntil(const std::function<bool()>& done, Timeout timeout);
  bool sendCommand(int8_t command, Timeout timeout);
  int linkIndex(const std::string& link) const;
  bool fail(std::string error);

  std::string m_name;
  std::string m_prefix;
  std::string m_clientId;
  std::unique_ptr<lcm::LCM> m_lcm;
  int64_t m_nextSeq = 1;
  std::string m_error;

  std::optional<rbsim::robot_state_t> m_state;
  uint64_t m_stateCount = 0;
  std::optional<rbsim::ack_t> m_lastAck;

  bool m_hasPending = false;
  double m_stateRate = 0.0;  // robot_command_t.state_rate: 0 leaves it
  int8_t m_dynamics = -1;    // robot_command_t.state_dynamics: −1 leaves it
  // The next message's joint entries (m_hasPending), kept between cycles so
  // that its vectors are not allocated again each cycle.
  rbsim::robot_command_t m_message;

  // This Robot's acks by (kind, seq).
  AckStore m_acks;
};

}  // namespace rbsim::client
