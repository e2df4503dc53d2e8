#pragma once
// A program the tests run as a separate process (rbserver, rbctl, the
// examples, the spy launcher), with its stdout and stderr in a file.
// The destructor kills and reaps a child that is still running, so a failing
// test never leaves processes behind.

#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace rbsim::e2e {

class ChildProcess {
 public:
  // Starts argv[0] (a path) with argv[1..]; stdout and stderr go to
  // `outputPath`. `environment` entries "NAME=VALUE" are added to (or replace
  // those of) the test's environment. Throws std::runtime_error when the
  // process cannot be started.
  ChildProcess(const std::vector<std::string>& argv, std::string outputPath,
               const std::vector<std::string>& environment = {});
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return m_pid; }
  // The exit status once the process has ended: its exit code, or 128 + the
  // signal that killed it. nullopt while it runs.
  std::optional<int> poll();
  std::optional<int> wait(std::chrono::milliseconds timeout);
  void signal(int signalNumber);
  // SIGTERM, then SIGKILL if it has not ended after `grace`; returns the status.
  int stop(std::chrono::milliseconds grace);
  // Everything it wrote so far.
  std::string output() const;
  const std::string& commandLine() const { return m_commandLine; }

 private:
  pid_t m_pid = -1;
  std::optional<int> m_status;
  std::string m_outputPath;
  std::string m_commandLine;
};

struct ProcessResult {
  std::optional<int> status;  // nullopt: it did not end within the timeout (then killed)
  std::string output;
};

// Runs a program to the end (or kills it after `timeout`).
ProcessResult runProcess(const std::vector<std::string>& argv, const std::string& outputPath,
                         std::chrono::milliseconds timeout,
                         const std::vector<std::string>& environment = {});

}  // namespace rbsim::e2e
