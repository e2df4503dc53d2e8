#pragma once
// A client of rbserver over LCM: the latest complete state, joint states,
// status and world description, and every wrench, command and joint command
// with its acknowledgement.
//
// Threading: none hidden. Messages are received and callbacks run only inside
// handle() / spinUntil() / waitForAck(), on the calling thread. A Client is
// not thread-safe: use it from one thread (or guard it with a mutex).
//
// Every request (wrench or command) gets a fresh sequence number; the server
// answers each with exactly one ack_t echoing (client id, seq), which
// waitForAck() returns. Acks are kept as they arrive, so waiting after the
// ack came in still finds it.
//
//   rbsim::client::Client client;                       // default URL and prefix
//   client.spinUntil([&] { return client.latestState().has_value(); }, 2s);
//   const auto ack = client.waitForAck(client.pause(), 1s);
//   if (!ack || !ack->accepted) ...                     // timeout / rejected (ack->reason)

#include <chrono>
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <set>
#include <optional>
#include <rbsim/ack_t.hpp>
#include <rbsim/command_t.hpp>
#include <rbsim/contacts_t.hpp>
#include <rbsim/joints_t.hpp>
#include <rbsim/status_t.hpp>
#include <rbsim/world_state_t.hpp>
#include <rbsim/world_t.hpp>
#include <string>
#include <utility>
#include <vector>

#include "rbsim/client/ack_store.h"
#include "rbsim/client/client_defaults.h"
#include "rbsim/client/joint_command.h"
#include "rbsim/client/page_assembler.h"
#include "rbsim/client/wrench.h"

namespace rbsim::client {

struct ClientOptions {
  std::string url;  // empty: $LCM_DEFAULT_URL, else kDefaultUrl
  std::string channelPrefix = kDefaultChannelPrefix;
  std::string clientId;  // empty: $RBSIM_CLIENT_ID, else makeDefaultClientId()
};

// Which channel a request went on, as ack_t::kind says.
enum class AckKind : int8_t { Wrench = 1, Command = 2, JointCommand = 3, RobotCommand = 4 };

// A request sent: what its ack will carry. `sent` is false when LCM could not
// publish it (no ack will come).
struct Request {
  int64_t seq = -1;
  AckKind kind = AckKind::Command;
  bool sent = false;
};

class Client {
 public:
  using Timeout = std::chrono::milliseconds;
  using CallbackId = uint64_t;
  using StateCallback = std::function<void(const rbsim::world_state_t&)>;
  using WorldCallback = std::function<void(const rbsim::world_t&)>;
  using StatusCallback = std::function<void(const rbsim::status_t&)>;
  using AckCallback = std::function<void(const rbsim::ack_t&)>;
  using ContactsCallback = std::function<void(const rbsim::contacts_t&)>;
  using JointsCallback = std::function<void(const rbsim::joints_t&)>;

  explicit Client(ClientOptions options = {});
  ~Client();
  // Registered with LCM by address: neither copyable nor movable.
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // False when LCM could not be opened (bad URL, no multicast route); every
  // other call then does nothing and waits time out.
  bool good() const;
  const std::string& url() const { return m_url; }
  const std::string& clientId() const { return m_clientId; }
  const std::string& channelPrefix() const { return m_prefix; }
  std::string channel(const std::string& suffix) const { return m_prefix + suffix; }

  // --- receiving -----------------------------------------------------------

  // Waits up to `timeout` for a message, then dispatches it and every other
  // message already waiting. Returns how many were dispatched (0 on timeout
  // or when a signal interrupted the wait), or −1 on an LCM error.
  int handle(Timeout timeout);
  // Handles messages until `done()` is true or `timeout` has passed; returns
  // done(). `done` is checked first, after every batch of messages and at
  // least every 50 ms, so it may also watch things other than messages.
  bool spinUntil(const std::function<bool()>& done, Timeout timeout);

  // The newest complete state (all its pages merged into one message, page 0
  // of 1), by arrival.
  const std::optional<rbsim::world_state_t>& latestState() const { return m_state; }
  // Complete states received so far (a lost page makes a step incomplete).
  uint64_t stateCount() const { return m_stateCount; }
  const std::optional<rbsim::status_t>& latestStatus() const { return m_status; }
  uint64_t statusCount() const { return m_statusCount; }
  // The newest complete world description (published at start, on change and
  // on publishWorld()).
  const std::optional<rbsim::world_t>& world() const { return m_world; }
  uint64_t worldCount() const { return m_worldCount; }
  // The newest complete contacts of a step (published on <prefix>CONTACTS
  // when the server's lcm.contacts_rate is above 0; contact_t has the
  // fields: body ids, point, normal, depth, impulses), pages merged.
  const std::optional<rbsim::contacts_t>& latestContacts() const { return m_contacts; }
  // The newest complete joint states of a step (<prefix>JOINTS, published
  // with every state of a world that has joints), pages merged.
  const std::optional<rbsim::joints_t>& latestJoints() const { return m_joints; }
  uint64_t jointsCount() const { return m_jointsCount; }
  // The joint called `name` in latestJoints(), or nullptr.
  const rbsim::joint_state_t* jointState(const std::string& name) const;
  // The joint called `name` in world(), or nullptr.
  const rbsim::joint_description_t* jointDescription(const std::string& name) const;

  // The server instance ids seen in statuses and acks (status_t.instance_id).
  const std::set<std::string>& serverInstances() const { return m_instances; }
  // Non-empty when two servers publish on this URL and prefix (two instance
  // ids seen, or a server's status reports another): a sentence saying so,
  // for the user. Their states interleave and a request gets two answers.
  std::string instanceConflict() const;
  uint64_t contactsCount() const { return m_contactsCount; }

  // Callbacks run inside handle() for every complete state / world
  // description, every status, and every ack (of any client). They may call
  // the sending methods but must not destroy the Client.
  CallbackId onState(StateCallback callback);
  CallbackId onWorld(WorldCallback callback);
  CallbackId onStatus(StatusCallback callback);
  CallbackId onAck(AckCallback callback);
  CallbackId onContacts(ContactsCallback callback);
  CallbackId onJoints(JointsCallback callback);
  void removeCallback(CallbackId id);

  // --- requests (each returns at once; wait with waitForAck) ---------------

  Request applyWrench(const Wrench& wrench);
  // MODE_CLEAR: this client's duration and persistent wrenches on `body`
  // (every body if empty), from `applyAtStep` (−1: the next step); with
  // `allClients`, MODE_CLEAR_ALL_CLIENTS: every client's. The ack's
  // wrenches_cleared says how many.
  Request clearWrenches(const std::string& body = "", int64_t applyAtStep = -1,
                        bool allClients = false);

  Request pause();
  Request resume();
  Request step(int64_t numSteps);              // the server must be paused
  Request reset();                             // back to the world loaded at start, step 0
  Request setRealTimeFactor(double factor);    // 0 = as fast as possible
  // One `bodies:` entry of the config schema, or a mapping with `bodies:`
  // and `joints:` lists as a world file has them (command_t.spawn_yaml).
  Request spawn(const std::string& yaml);
  Request remove(const std::string& body);        // the body and its joints
  Request removeJoint(const std::string& joint);  // the joint alone
  Request publishWorld();

  // A joint_command_t on <prefix>JOINT_COMMAND, answered by an ack of kind
  // JointCommand.
  Request commandJoint(const JointCommand& command);

  // The ack answering (this client, seq, kind), handling messages while it is
  // not there yet; nullopt after `timeout`. A rejection is an ack with
  // accepted == false and a reason.
  std::optional<rbsim::ack_t> waitForAck(int64_t seq, AckKind kind, Timeout timeout);
  std::optional<rbsim::ack_t> waitForAck(const Request& request, Timeout timeout);

  // The underlying connection, for what this class does not cover (raw
  // publishing, select() on lcm().getFileno()).
  lcm::LCM& lcm() { return *m_lcm; }

 private:
  template <class Callback>
  struct Registered {
    CallbackId id;
    Callback callback;
  };

  void onStateMessage(const lcm::ReceiveBuffer*, const std::string&,
                      const rbsim::world_state_t* page);
  void onWorldMessage(const lcm::ReceiveBuffer*, const std::string&, const rbsim::world_t* page);
  void onStatusMessage(const lcm::ReceiveBuffer*, const std::string&,
                       const rbsim::status_t* status);
  void onAckMessage(const lcm::ReceiveBuffer*, const std::string&, const rbsim::ack_t* ack);
  void onContactsMessage(const lcm::ReceiveBuffer*, const std::string&,
                         const rbsim::contacts_t* page);
  void onJointsMessage(const lcm::ReceiveBuffer*, const std::string&, const rbsim::joints_t* page);
  Request sendCommand(int8_t command, const std::function<void(rbsim::command_t&)>& fill);
  template <class Message>
  bool publish(const std::string& suffix, const Message& message);

  std::string m_url;
  std::string m_prefix;
  std::string m_clientId;
  std::unique_ptr<lcm::LCM> m_lcm;
  int64_t m_nextSeq = 1;

  PageAssembler<rbsim::world_state_t> m_statePages;
  PageAssembler<rbsim::world_t> m_worldPages;
  PageAssembler<rbsim::contacts_t> m_contactsPages;
  std::optional<rbsim::contacts_t> m_contacts;
  uint64_t m_contactsCount = 0;
  PageAssembler<rbsim::joints_t> m_jointsPages;
  std::optional<rbsim::joints_t> m_joints;
  uint64_t m_jointsCount = 0;
  std::set<std::string> m_instances;
  std::string m_reportedOther;  // status_t.other_instance_id of the latest status
  std::optional<rbsim::world_state_t> m_state;
  std::optional<rbsim::status_t> m_status;
  std::optional<rbsim::world_t> m_world;
  uint64_t m_stateCount = 0;
  uint64_t m_statusCount = 0;
  uint64_t m_worldCount = 0;

  // This client's acks by (kind, seq).
  AckStore m_acks;

  CallbackId m_nextCallbackId = 1;
  std::vector<Registered<StateCallback>> m_stateCallbacks;
  std::vector<Registered<WorldCallback>> m_worldCallbacks;
  std::vector<Registered<StatusCallback>> m_statusCallbacks;
  std::vector<Registered<AckCallback>> m_ackCallbacks;
  std::vector<Registered<ContactsCallback>> m_contactsCallbacks;
  std::vector<Registered<JointsCallback>> m_jointsCallbacks;
};

}  // namespace rbsim::client
