#include "rbsim/client/client.h"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdlib>
#include <rbsim/command_t.hpp>
#include <rbsim/joint_command_t.hpp>
#include <rbsim/wrench_t.hpp>
#include <string_view>

#include "wire_helpers.h"

namespace rbsim::client {

static_assert(static_cast<int8_t>(Frame::World) == rbsim::wrench_t::FRAME_WORLD);
static_assert(static_cast<int8_t>(Frame::Body) == rbsim::wrench_t::FRAME_BODY);
static_assert(static_cast<int8_t>(WrenchMode::OneStep) == rbsim::wrench_t::MODE_ONE_STEP);
static_assert(static_cast<int8_t>(WrenchMode::Duration) == rbsim::wrench_t::MODE_DURATION);
static_assert(static_cast<int8_t>(WrenchMode::Persistent) == rbsim::wrench_t::MODE_PERSISTENT);
static_assert(static_cast<int8_t>(WrenchMode::Clear) == rbsim::wrench_t::MODE_CLEAR);
static_assert(static_cast<int8_t>(WrenchMode::ClearAllClients) ==
              rbsim::wrench_t::MODE_CLEAR_ALL_CLIENTS);
static_assert(static_cast<int8_t>(AckKind::Wrench) == rbsim::ack_t::KIND_WRENCH);
static_assert(static_cast<int8_t>(AckKind::Command) == rbsim::ack_t::KIND_COMMAND);
static_assert(static_cast<int8_t>(AckKind::JointCommand) == rbsim::ack_t::KIND_JOINT_COMMAND);
static_assert(static_cast<int8_t>(AckKind::RobotCommand) == rbsim::ack_t::KIND_ROBOT_COMMAND);
static_assert(static_cast<int8_t>(JointMode::Off) == rbsim::joint_command_t::MODE_OFF);
static_assert(static_cast<int8_t>(JointMode::Velocity) == rbsim::joint_command_t::MODE_VELOCITY);
static_assert(static_cast<int8_t>(JointMode::Position) == rbsim::joint_command_t::MODE_POSITION);
static_assert(static_cast<int8_t>(JointMode::Effort) == rbsim::joint_command_t::MODE_EFFORT);

namespace {

using detail::kQueueCapacity;
using detail::regexEscaped;
using detail::wallMicroseconds;


void copyVec3(double (&out)[3], const Vec3& in) {
  std::copy(in.begin(), in.end(), out);
}

template <class Callbacks, class Message>
void notify(const Callbacks& callbacks, const Message& message) {
  // A copy, so that a callback may add or remove callbacks.
  const Callbacks snapshot = callbacks;
  for (const auto& registered : snapshot) registered.callback(message);
}

}  // namespace

Client::Client(ClientOptions options)
    : m_url(resolveLcmUrl(options.url)),
      m_prefix(std::move(options.channelPrefix)),
      m_clientId(resolveClientId(options.clientId)),
      m_lcm(std::make_unique<lcm::LCM>(m_url)) {
  // A named client id may outlive this process: start its sequence numbers
  // at the wall clock in microseconds, so that they keep increasing across
  // runs (wrench_t.seq) and an ack of an earlier run never answers this one.
  const char* named = std::getenv("RBSIM_CLIENT_ID");
  if (!options.clientId.empty() || (named != nullptr && *named != '\0'))
    m_nextSeq = wallMicroseconds();
  if (!m_lcm->good()) return;
  m_lcm->subscribe(regexEscaped(channel("STATE")), &Client::onStateMessage, this)
      ->setQueueCapacity(kQueueCapacity);
  m_lcm->subscribe(regexEscaped(channel("WORLD")), &Client::onWorldMessage, this)
      ->setQueueCapacity(kQueueCapacity);
  m_lcm->subscribe(regexEscaped(channel("STATUS")), &Client::onStatusMessage, this)
      ->setQueueCapacity(kQueueCapacity);
  m_lcm->subscribe(regexEscaped(channel("ACK")), &Client::onAckMessage, this)
      ->setQueueCapacity(kQueueCapacity);
  m_lcm->subscribe(regexEscaped(channel("CONTACTS")), &Client::onContactsMessage, this)
      ->setQueueCapacity(kQueueCapacity);
  m_lcm->subscribe(regexEscaped(channel("JOINTS")), &Client::onJointsMessage, this)
      ->setQueueCapacity(kQueueCapacity);
}

Client::~Client() = default;

bool Client::good() const {
  return m_lcm->good();
}

int Client::handle(Timeout timeout) {
  if (!good()) return -1;
  return detail::handleMessages(*m_lcm, timeout);
}

bool Client::spinUntil(const std::function<bool()>& done, Timeout timeout) {
  return detail::spinUntil([this](Timeout slice) { return handle(slice); }, [this] { return good(); }, done, timeout);
}

Client::CallbackId Client::onState(StateCallback callback) {
  m_stateCallbacks.push_back({m_nextCallbackId, std::move(callback)});
  return m_nextCallbackId++;
}

Client::CallbackId Client::onWorld(WorldCallback callback) {
  m_worldCallbacks.push_back({m_nextCallbackId, std::move(callback)});
  return m_nextCallbackId++;
}

Client::CallbackId Client::onStatus(StatusCallback callback) {
  m_statusCallbacks.push_back({m_nextCallbackId, std::move(callback)});
  return m_nextCallbackId++;
}

Client::CallbackId Client::onAck(AckCallback callback) {
  m_ackCallbacks.push_back({m_nextCallbackId, std::move(callback)});
  return m_nextCallbackId++;
}

Client::CallbackId Client::onContacts(ContactsCallback callback) {
  m_contactsCallbacks.push_back({m_nextCallbackId, std::move(callback)});
  return m_nextCallbackId++;
}

Client::CallbackId Client::onJoints(JointsCallback callback) {
  m_jointsCallbacks.push_back({m_nextCallbackId, std::move(callback)});
  return m_nextCallbackId++;
}

void Client::removeCallback(CallbackId id) {
  const auto hasId = [id](const auto& registered) { return registered.id == id; };
  std::erase_if(m_stateCallbacks, hasId);
  std::erase_if(m_worldCallbacks, hasId);
  std::erase_if(m_statusCallbacks, hasId);
  std::erase_if(m_ackCallbacks, hasId);
  std::erase_if(m_contactsCallbacks, hasId);
  std::erase_if(m_jointsCallbacks, hasId);
}

void Client::onStateMessage(const lcm::ReceiveBuffer*, const std::string&,
                            const rbsim::world_state_t* page) {
  auto whole = m_statePages.add(*page);
  if (!whole) return;
  m_state = std::move(*whole);
  ++m_stateCount;
  notify(m_stateCallbacks, *m_state);
}

void Client::onWorldMessage(const lcm::ReceiveBuffer*, const std::string&,
                            const rbsim::world_t* page) {
  auto whole = m_worldPages.add(*page);
  if (!whole) return;
  m_world = std::move(*whole);
  ++m_worldCount;
  notify(m_worldCallbacks, *m_world);
}

void Client::onContactsMessage(const lcm::ReceiveBuffer*, const std::string&,
                               const rbsim::contacts_t* page) {
  auto whole = m_contactsPages.add(*page);
  if (!whole) return;
  m_contacts = std::move(*whole);
  ++m_contactsCount;
  notify(m_contactsCallbacks, *m_contacts);
}

void Client::onJointsMessage(const lcm::ReceiveBuffer*, const std::string&, const rbsim::joints_t* page) {
  auto whole = m_jointsPages.add(*page);
  if (!whole) return;
  m_joints = std::move(*whole);
  ++m_jointsCount;
  notify(m_jointsCallbacks, *m_joints);
}

const rbsim::joint_state_t* Client::jointState(const std::string& name) const {
  if (!m_joints) return nullptr;
  for (const auto& joint : m_joints->joints)
    if (joint.name == name) return &joint;
  return nullptr;
}

const rbsim::joint_description_t* Client::jointDescription(const std::string& name) const {
  if (!m_world) return nullptr;
  for (const auto& joint : m_world->joints)
    if (joint.name == name) return &joint;
  return nullptr;
}

void Client::onStatusMessage(const lcm::ReceiveBuffer*, const std::string&,
                             const rbsim::status_t* status) {
  m_status = *status;
  ++m_statusCount;
  if (!status->instance_id.empty()) m_instances.insert(status->instance_id);
  m_reportedOther = status->other_instance_id;
  notify(m_statusCallbacks, *m_status);
}

void Client::onAckMessage(const lcm::ReceiveBuffer*, const std::string&, const rbsim::ack_t* ack) {
  if (ack->client == m_clientId) {
    if (!ack->instance_id.empty()) m_instances.insert(ack->instance_id);
    m_acks.add(*ack);
  }
  notify(m_ackCallbacks, *ack);
}

std::string Client::instanceConflict() const {
  std::string ids;
  for (const std::string& id : m_instances) ids += (ids.empty() ? "" : ", ") + id;
  if (m_instances.size() >= 2)
    return "two servers publish on prefix '" + m_prefix + "' of " + m_url + " (instances " + ids +
           "): their states interleave and requests are answered twice; stop one or give it "
           "another --channel-prefix";
  if (!m_reportedOther.empty())
    return "the server on prefix '" + m_prefix + "' hears another server there (instance " +
           m_reportedOther + "): their states interleave; stop one or give it another "
           "--channel-prefix";
  return "";
}

template <class Message>
bool Client::publish(const std::string& suffix, const Message& message) {
  return good() && m_lcm->publish(channel(suffix), &message) == 0;
}

Request Client::applyWrench(const Wrench& wrench) {
  rbsim::wrench_t message;
  message.utime = wallMicroseconds();
  message.client = m_clientId;
  message.seq = m_nextSeq++;
  message.body = wrench.body;
  message.frame = static_cast<int8_t>(wrench.frame);
  // No point: the server puts it at the centre of mass, exactly, when the
  // wrench first acts.
  message.point_frame =
      wrench.point ? static_cast<int8_t>(wrench.pointFrame.value_or(wrench.frame))
                   : rbsim::wrench_t::POINT_FRAME_CENTER_OF_MASS;
  copyVec3(message.force, wrench.force);
  copyVec3(message.torque, wrench.torque);
  copyVec3(message.point, wrench.point.value_or(Vec3{0.0, 0.0, 0.0}));
  message.mode = static_cast<int8_t>(wrench.mode);
  message.duration = wrench.duration;
  message.apply_at_step = wrench.applyAtStep;
  return {message.seq, AckKind::Wrench, publish("WRENCH", message)};
}

Request Client::clearWrenches(const std::string& body, int64_t applyAtStep, bool allClients) {
  Wrench clear;
  clear.body = body;
  clear.mode = allClients ? WrenchMode::ClearAllClients : WrenchMode::Clear;
  clear.applyAtStep = applyAtStep;
  return applyWrench(clear);
}

Request Client::sendCommand(int8_t command, const std::function<void(rbsim::command_t&)>& fill) {
  rbsim::command_t message;
  message.utime = wallMicroseconds();
  message.client = m_clientId;
  message.seq = m_nextSeq++;
  message.command = command;
  message.num_steps = 0;
  message.real_time_factor = 0.0;
  if (fill) fill(message);
  return {message.seq, AckKind::Command, publish("COMMAND", message)};
}

Request Client::pause() {
  return sendCommand(rbsim::command_t::PAUSE, {});
}

Request Client::resume() {
  return sendCommand(rbsim::command_t::RESUME, {});
}

Request Client::step(int64_t numSteps) {
  return sendCommand(rbsim::command_t::STEP, [&](rbsim::command_t& m) { m.num_steps = numSteps; });
}

Request Client::reset() {
  return sendCommand(rbsim::command_t::RESET, {});
}

Request Client::setRealTimeFactor(double factor) {
  return sendCommand(rbsim::command_t::SET_REAL_TIME_FACTOR,
                     [&](rbsim::command_t& m) { m.real_time_factor = factor; });
}

Request Client::spawn(const std::string& yaml) {
  return sendCommand(rbsim::command_t::SPAWN,
                     [&](rbsim::command_t& m) { m.spawn_yaml = yaml; });
}

Request Client::remove(const std::string& body) {
  return sendCommand(rbsim::command_t::REMOVE, [&](rbsim::command_t& m) { m.body = body; });
}

Request Client::removeJoint(const std::string& joint) {
  return sendCommand(rbsim::command_t::REMOVE, [&](rbsim::command_t& m) { m.joint = joint; });
}

Request Client::publishWorld() {
  return sendCommand(rbsim::command_t::PUBLISH_WORLD, {});
}

Request Client::commandJoint(const JointCommand& command) {
  rbsim::joint_command_t message;
  message.utime = wallMicroseconds();
  message.client = m_clientId;
  message.seq = m_nextSeq++;
  message.joint = command.joint;
  message.mode = static_cast<int8_t>(command.mode);
  message.target = command.target;
  message.max_effort = command.maxEffort;
  message.stiffness = command.stiffness;
  message.damping = command.damping;
  message.apply_at_step = command.applyAtStep;
  return {message.seq, AckKind::JointCommand, publish("JOINT_COMMAND", message)};
}

std::optional<rbsim::ack_t> Client::waitForAck(int64_t seq, AckKind kind, Timeout timeout) {
  const std::pair<int8_t, int64_t> key{static_cast<int8_t>(kind), seq};
  spinUntil([&] { return m_acks.find(key) != nullptr; }, timeout);
  const rbsim::ack_t* found = m_acks.find(key);
  if (found == nullptr) return std::nullopt;
  return *found;
}

std::optional<rbsim::ack_t> Client::waitForAck(const Request& request, Timeout timeout) {
  if (!request.sent) return std::nullopt;
  return waitForAck(request.seq, request.kind, timeout);
}

}  // namespace rbsim::client
