#pragma once
// SIGINT, SIGTERM and SIGHUP as events on a file descriptor (signalfd), so
// the single-threaded loop sees them in the same poll as LCM messages and
// timers; no handler does work asynchronously. The signals are blocked for
// the whole process, so they can only arrive through the descriptor.

namespace rbsim {

enum class SignalEvent { None, Stop, Hangup };

class SignalEvents {
 public:
  SignalEvents();  // blocks the signals and opens the descriptor
  ~SignalEvents();
  SignalEvents(const SignalEvents&) = delete;
  SignalEvents& operator=(const SignalEvents&) = delete;

  int fileDescriptor() const { return m_fd; }
  bool ok() const { return m_fd >= 0; }
  // Reads one pending signal without blocking.
  SignalEvent read();

 private:
  int m_fd = -1;
};

}  // namespace rbsim
