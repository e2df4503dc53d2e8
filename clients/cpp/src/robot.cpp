#include "rbsim/client/robot.h"

#include <Eigen/Geometry>  // cross()
#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <rbsim/command_t.hpp>

#include "wire_helpers.h"

namespace rbsim::client {

namespace {

using detail::wallMicroseconds;


const std::vector<std::string> kNoNames;
const std::string kNoNote;

Eigen::VectorXd vectorOf(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

}  // namespace

Robot::Robot(std::string name, ClientOptions options)
    : m_name(std::move(name)),
      m_prefix(std::move(options.channelPrefix)),
      m_clientId(resolveClientId(options.clientId)),
      m_lcm(std::make_unique<lcm::LCM>(resolveLcmUrl(options.url))) {
  // As Client: a named id may outlive this process, so its sequence numbers
  // start at the wall clock and an ack of an earlier run never answers this one.
  const char* named = std::getenv("RBSIM_CLIENT_ID");
  if (!options.clientId.empty() || (named != nullptr && *named != '\0'))
    m_nextSeq = wallMicroseconds();
  if (!m_lcm->good()) return;
  m_lcm->subscribe(detail::regexEscaped(m_prefix + "ROBOT_STATE"), &Robot::onState, this)
      ->setQueueCapacity(detail::kQueueCapacity);
  m_lcm->subscribe(detail::regexEscaped(m_prefix + "ACK"), &Robot::onAck, this)
      ->setQueueCapacity(detail::kQueueCapacity);
}

Robot::~Robot() = default;

bool Robot::good() const {
  return m_lcm->good();
}

bool Robot::fail(std::string error) {
  m_error = std::move(error);
  return false;
}

// --- receiving ---------------------------------------------------------------

void Robot::onState(const lcm::ReceiveBuffer*, const std::string&,
                    const rbsim::robot_state_t* state) {
  if (state->robot != m_name) return;  // every robot of the world publishes on one channel
  m_state = *state;
  ++m_stateCount;
}

void Robot::onAck(const lcm::ReceiveBuffer*, const std::string&, const rbsim::ack_t* ack) {
  if (ack->client != m_clientId) return;
  m_acks.add(*ack);
}

int Robot::handle(Timeout timeout) {
  if (!good()) return -1;
  return detail::handleMessages(*m_lcm, timeout);
}

bool Robot::spinUntil(const std::function<bool()>& done, Timeout timeout) {
  return detail::spinUntil([this](Timeout slice) { return handle(slice); }, [this] { return good(); }, done, timeout);
}

bool Robot::waitForState(Timeout timeout, bool withDynamics) {
  const auto ready = [&] {
    return m_state && (!withDynamics || m_state->num_dofs > 0 || !m_state->dynamics_note.empty());
  };
  if (spinUntil(ready, timeout)) return true;
  return fail("no state of robot '" + m_name + "'" + (withDynamics ? " with its dynamics" : "") +
              " on " + m_prefix + "ROBOT_STATE within " + std::to_string(timeout.count()) + " ms");
}

bool Robot::waitForStep(int64_t step, Timeout timeout) {
  if (spinUntil([&] { return m_state && m_state->step >= step; }, timeout)) return true;
  return fail("no state of robot '" + m_name + "' at step " + std::to_string(step) + " within " +
              std::to_string(timeout.count()) + " ms (newest: " +
              (m_state ? std::to_string(m_state->step) : std::string("none")) + ")");
}

const std::vector<std::string>& Robot::jointNames() const {
  return m_state ? m_state->joint_names : kNoNames;
}

int64_t Robot::step() const {
  return m_state ? m_state->step : -1;
}

double Robot::simTime() const {
  return m_state ? m_state->sim_time : std::numeric_limits<double>::quiet_NaN();
}

Eigen::VectorXd Robot::q() const {
  return m_state ? vectorOf(m_state->position) : Eigen::VectorXd();
}

Eigen::VectorXd Robot::qd() const {
  return m_state ? vectorOf(m_state->velocity) : Eigen::VectorXd();
}

Eigen::VectorXd Robot::tau() const {
  return m_state ? vectorOf(m_state->effort) : Eigen::VectorXd();
}

bool Robot::hasDynamics() const {
  return m_state && m_state->num_dofs > 0;
}

const std::string& Robot::dynamicsNote() const {
  return m_state ? m_state->dynamics_note : kNoNote;
}

Eigen::MatrixXd Robot::massMatrix() const {
  if (!hasDynamics()) return {};
  const int n = m_state->num_dofs;
  Eigen::MatrixXd mass(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) mass(i, j) = m_state->mass_matrix[i][j];
  return mass;
}

Eigen::VectorXd Robot::bias() const {
  return hasDynamics() ? vectorOf(m_state->bias) : Eigen::VectorXd();
}

Eigen::VectorXd Robot::gravity() const {
  return hasDynamics() ? vectorOf(m_state->gravity) : Eigen::VectorXd();
}

const std::vector<std::string>& Robot::linkNames() const {
  return m_state ? m_state->link_names : kNoNames;
}

int Robot::linkIndex(const std::string& link) const {
  if (!m_state) return -1;
  const std::string full = m_name + "/" + link;
  const auto& names = m_state->link_names;
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == link || names[i] == full) return static_cast<int>(i);
  return -1;
}

std::optional<LinkPose> Robot::linkPose(const std::string& link) const {
  const int index = linkIndex(link);
  if (index < 0) return std::nullopt;
  const auto& p = m_state->link_position[index];
  const auto& o = m_state->link_orientation[index];
  return LinkPose{{p[0], p[1], p[2]}, {o[0], o[1], o[2], o[3]}};
}

std::optional<Eigen::MatrixXd> Robot::jacobian(const std::string& link) const {
  const int index = linkIndex(link);
  if (index < 0) return std::nullopt;
  const int n = m_state->num_dofs;
  Eigen::MatrixXd jacobian(6, n);
  const auto& rows = m_state->link_jacobian[index];
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < n; ++c) jacobian(r, c) = rows[r][c];
  return jacobian;
}

std::optional<Eigen::MatrixXd> Robot::jacobian(const std::string& link,
                                               const Eigen::Vector3d& worldPoint) const {
  auto jacobian = this->jacobian(link);
  if (!jacobian) return std::nullopt;
  // A point r from the frame's origin moves at v + w × r = v − r × w.
  const auto& o = m_state->link_position[linkIndex(link)];
  const Eigen::Vector3d r = worldPoint - Eigen::Vector3d(o[0], o[1], o[2]);
  for (Eigen::Index c = 0; c < jacobian->cols(); ++c) {
    const Eigen::Vector3d w = jacobian->block<3, 1>(3, c);
    jacobian->block<3, 1>(0, c) -= r.cross(w);
  }
  return jacobian;
}

// --- commanding --------------------------------------------------------------

bool Robot::command(const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                    const Eigen::VectorXd& tauFF, const Eigen::VectorXd& kp,
                    const Eigen::VectorXd& kd) {
  if (!m_state) return fail("no state of robot '" + m_name + "' yet: its joints are not known");
  const int n = m_state->num_joints;
  for (const auto* v : {&q, &qd, &tauFF, &kp, &kd})
    if (v->size() != n)
      return fail("robot '" + m_name + "' has " + std::to_string(n) +
                  " joints; a command vector has " + std::to_string(v->size()) + " entries");
  auto& m = m_message;
  m.num_joints = n;
  m.num_names = 0;
  m.joint_names.clear();
  m.mode.resize(n);
  for (auto* field : {&m.position, &m.velocity, &m.effort, &m.stiffness, &m.damping, &m.max_effort})
    field->resize(n);
  for (int i = 0; i < n; ++i) {
    const bool drive = kp[i] != 0.0 || kd[i] != 0.0;  // a negative gain: the server refuses it
    m.mode[i] = m_state->leader[i] >= 0 ? rbsim::robot_command_t::MODE_KEEP
                : drive                 ? rbsim::robot_command_t::MODE_POSITION
                                        : rbsim::robot_command_t::MODE_EFFORT;
    m.position[i] = q[i];
    m.velocity[i] = qd[i];
    m.effort[i] = tauFF[i];
    m.stiffness[i] = kp[i];
    m.damping[i] = kd[i];
    m.max_effort[i] = 0.0;  // MODE_POSITION: uncapped (the joint's own limits still hold)
  }
  m_hasPending = true;
  return true;
}

bool Robot::commandEffort(const Eigen::VectorXd& tau) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(tau.size());
  return command(zero, zero, tau, zero, zero);
}

void Robot::commandRaw(const rbsim::robot_command_t& message) {
  auto& m = m_message;
  m.num_joints = message.num_joints;
  m.num_names = message.num_names;
  m.joint_names = message.joint_names;
  m.mode = message.mode;
  m.position = message.position;
  m.velocity = message.velocity;
  m.effort = message.effort;
  m.stiffness = message.stiffness;
  m.damping = message.damping;
  m.max_effort = message.max_effort;
  m_hasPending = true;
}

Request Robot::send(int64_t applyAtStep, int32_t steps) {
  auto& m = m_message;
  m.utime = wallMicroseconds();
  m.client = m_clientId;
  m.seq = m_nextSeq++;
  m.robot = m_name;
  m.apply_at_step = applyAtStep;
  if (!m_hasPending) {
    // Change no joint: the settings or the steps alone. clear() keeps the
    // vectors' storage for the next command.
    m.num_joints = 0;
    m.num_names = 0;
    for (auto* field :
         {&m.position, &m.velocity, &m.effort, &m.stiffness, &m.damping, &m.max_effort})
      field->clear();
    m.mode.clear();
    m.joint_names.clear();
  }
  m.state_rate = m_stateRate;
  m.state_dynamics = m_dynamics;
  m.steps = steps;
  const bool sent = good() && m_lcm->publish(m_prefix + "ROBOT_COMMAND", &m) == 0;
  // The server keeps what it accepts; a refusal is the caller's to see in
  // the ack and to send again.
  m_hasPending = false;
  m_stateRate = 0.0;
  m_dynamics = -1;
  return {m.seq, AckKind::RobotCommand, sent};
}

std::optional<rbsim::ack_t> Robot::waitForAck(const Request& request, Timeout timeout) {
  if (!request.sent) return std::nullopt;
  const std::pair<int8_t, int64_t> key{static_cast<int8_t>(request.kind), request.seq};
  spinUntil([&] { return m_acks.find(key) != nullptr; }, timeout);
  const rbsim::ack_t* found = m_acks.find(key);
  if (found == nullptr) return std::nullopt;
  return *found;
}

bool Robot::stepSync(int32_t steps, Timeout timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  const auto left = [&] {
    return std::max(Timeout{0},
                    std::chrono::ceil<Timeout>(deadline - std::chrono::steady_clock::now()));
  };
  // Only a state that arrives after the command counts: after a RESET the
  // newest state held may be of a later step than the one waited for.
  const uint64_t before = m_stateCount;
  const Request request = send(-1, steps);
  if (!request.sent) return fail("could not publish on " + m_prefix + "ROBOT_COMMAND");
  const auto ack = waitForAck(request, left());
  m_lastAck = ack;
  if (!ack)
    return fail("no ack of robot command seq " + std::to_string(request.seq) + " within " +
                std::to_string(timeout.count()) + " ms");
  if (!ack->accepted) return fail("robot command refused: " + ack->reason);
  // The command acts from effective_step, the first of the steps; the state
  // after the last of them is the one to wait for.
  const int64_t last = ack->effective_step + std::max(steps, 1) - 1;
  if (spinUntil([&] { return m_stateCount > before && m_state->step >= last; }, left()))
    return true;
  return fail("no state of robot '" + m_name + "' at step " + std::to_string(last) + " within " +
              std::to_string(timeout.count()) + " ms (newest: " +
              (m_state ? std::to_string(m_state->step) : std::string("none")) + ")");
}

bool Robot::sendCommand(int8_t command, Timeout timeout) {
  rbsim::command_t message;
  message.utime = wallMicroseconds();
  message.client = m_clientId;
  message.seq = m_nextSeq++;
  message.command = command;
  message.num_steps = 0;
  message.real_time_factor = 0.0;
  const Request request{message.seq, AckKind::Command,
                        good() && m_lcm->publish(m_prefix + "COMMAND", &message) == 0};
  const auto ack = waitForAck(request, timeout);
  if (!ack) return fail("no ack of command seq " + std::to_string(request.seq));
  if (!ack->accepted) return fail("command refused: " + ack->reason);
  return true;
}

bool Robot::pause(Timeout timeout) {
  return sendCommand(rbsim::command_t::PAUSE, timeout);
}

bool Robot::resume(Timeout timeout) {
  return sendCommand(rbsim::command_t::RESUME, timeout);
}

}  // namespace rbsim::client
