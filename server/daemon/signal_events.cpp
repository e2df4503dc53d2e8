#include "daemon/signal_events.h"

#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

namespace rbsim {

SignalEvents::SignalEvents() {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGHUP);
  if (sigprocmask(SIG_BLOCK, &signals, nullptr) != 0) return;
  m_fd = signalfd(-1, &signals, SFD_NONBLOCK | SFD_CLOEXEC);
}

SignalEvents::~SignalEvents() {
  if (m_fd >= 0) close(m_fd);
}

SignalEvent SignalEvents::read() {
  signalfd_siginfo info{};
  if (m_fd < 0 || ::read(m_fd, &info, sizeof info) != static_cast<ssize_t>(sizeof info))
    return SignalEvent::None;
  if (info.ssi_signo == SIGHUP) return SignalEvent::Hangup;
  return SignalEvent::Stop;
}

}  // namespace rbsim
