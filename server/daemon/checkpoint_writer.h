#pragma once
// Periodic checkpoints written off the stepping thread: encoding a session
// takes microseconds to milliseconds, but fsync can take tens of
// milliseconds, far more than a 1 ms step. The stepping thread hands over
// the encoded bytes; a writer thread writes them atomically. If a write is
// still in progress when the next checkpoint comes, the newer one replaces
// the one waiting (only the latest matters), so memory stays bounded at two
// checkpoints.

#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace rbsim {

class CheckpointWriter {
 public:
  CheckpointWriter() = default;
  ~CheckpointWriter();
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  // Queues `fileBytes` (a whole checkpoint file) for `path`; starts the
  // thread on first use.
  void submit(std::string path, std::vector<uint8_t> fileBytes, int64_t step);
  // Writes what is still waiting, then stops the thread.
  void finish();

  int64_t written() const;
  int64_t failed() const;
  int64_t superseded() const;  // replaced before they were written

 private:
  struct Job {
    std::string path;
    std::vector<uint8_t> bytes;
    int64_t step = 0;
  };
  void run();

  mutable std::mutex m_mutex;
  std::condition_variable m_wake;
  std::optional<Job> m_waiting;
  bool m_stopping = false;
  int64_t m_written = 0;
  int64_t m_failed = 0;
  int64_t m_superseded = 0;
  std::thread m_thread;
};

}  // namespace rbsim
