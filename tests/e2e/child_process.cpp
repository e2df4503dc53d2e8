#include "child_process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace rbsim::e2e {

namespace {

std::vector<std::string> mergedEnvironment(const std::vector<std::string>& overrides) {
  std::vector<std::string> merged;
  const auto nameOf = [](const std::string& entry) { return entry.substr(0, entry.find('=')); };
  for (char** entry = environ; *entry != nullptr; ++entry) {
    const std::string current = *entry;
    bool overridden = false;
    for (const auto& override : overrides) overridden |= nameOf(override) == nameOf(current);
    if (!overridden) merged.push_back(current);
  }
  merged.insert(merged.end(), overrides.begin(), overrides.end());
  return merged;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (auto& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

int statusFrom(int waitStatus) {
  if (WIFEXITED(waitStatus)) return WEXITSTATUS(waitStatus);
  if (WIFSIGNALED(waitStatus)) return 128 + WTERMSIG(waitStatus);
  return -1;
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv, std::string outputPath,
                           const std::vector<std::string>& environment)
    : m_outputPath(std::move(outputPath)) {
  if (argv.empty()) throw std::runtime_error("ChildProcess: empty argv");
  for (const auto& argument : argv) m_commandLine += (m_commandLine.empty() ? "" : " ") + argument;

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, m_outputPath.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);

  std::vector<std::string> arguments = argv;
  std::vector<std::string> environmentStrings = mergedEnvironment(environment);
  auto argumentPointers = pointers(arguments);
  auto environmentPointers = pointers(environmentStrings);
  const int error = posix_spawn(&m_pid, argv[0].c_str(), &actions, nullptr, argumentPointers.data(),
                                environmentPointers.data());
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0)
    throw std::runtime_error("cannot start '" + m_commandLine + "': " + std::strerror(error));
}

ChildProcess::~ChildProcess() {
  if (!poll()) {
    ::kill(m_pid, SIGKILL);
    int waitStatus = 0;
    ::waitpid(m_pid, &waitStatus, 0);
  }
}

std::optional<int> ChildProcess::poll() {
  if (m_status) return m_status;
  int waitStatus = 0;
  const pid_t done = ::waitpid(m_pid, &waitStatus, WNOHANG);
  if (done == m_pid) m_status = statusFrom(waitStatus);
  return m_status;
}

std::optional<int> ChildProcess::wait(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!poll() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  return m_status;
}

void ChildProcess::signal(int signalNumber) {
  if (!poll()) ::kill(m_pid, signalNumber);
}

int ChildProcess::stop(std::chrono::milliseconds grace) {
  signal(SIGTERM);
  if (const auto status = wait(grace)) return *status;
  signal(SIGKILL);
  return wait(std::chrono::seconds(10)).value_or(-1);
}

std::string ChildProcess::output() const {
  std::ifstream file(m_outputPath);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

ProcessResult runProcess(const std::vector<std::string>& argv, const std::string& outputPath,
                         std::chrono::milliseconds timeout,
                         const std::vector<std::string>& environment) {
  ChildProcess child(argv, outputPath, environment);
  ProcessResult result;
  result.status = child.wait(timeout);
  if (!result.status) child.stop(std::chrono::milliseconds(500));
  result.output = child.output();
  return result;
}

}  // namespace rbsim::e2e
