#include "daemon/checkpoint_writer.h"

#include "daemon/log.h"
#include "persist/checkpoint_file.h"

namespace rbsim {

CheckpointWriter::~CheckpointWriter() { finish(); }

void CheckpointWriter::submit(std::string path, std::vector<uint8_t> fileBytes, int64_t step) {
  std::lock_guard lock(m_mutex);
  if (m_waiting) ++m_superseded;
  m_waiting = Job{std::move(path), std::move(fileBytes), step};
  if (!m_thread.joinable()) m_thread = std::thread(&CheckpointWriter::run, this);
  m_wake.notify_one();
}

void CheckpointWriter::finish() {
  {
    std::lock_guard lock(m_mutex);
    m_stopping = true;
    m_wake.notify_one();
  }
  if (m_thread.joinable()) m_thread.join();
}

void CheckpointWriter::run() {
  std::unique_lock lock(m_mutex);
  while (true) {
    m_wake.wait(lock, [&] { return m_waiting.has_value() || m_stopping; });
    if (!m_waiting) return;  // stopping with nothing left
    Job job = std::move(*m_waiting);
    m_waiting.reset();
    lock.unlock();
    const auto written = writeFileAtomically(job.path, job.bytes);
    if (written) {
      logDebug("checkpoint of step " + std::to_string(job.step) + " written to " + job.path);
    } else {
      logWarning("periodic checkpoint of step " + std::to_string(job.step) + " failed: " + written.error().message);
    }
    lock.lock();
    ++(written ? m_written : m_failed);
  }
}

int64_t CheckpointWriter::written() const {
  std::lock_guard lock(m_mutex);
  return m_written;
}

int64_t CheckpointWriter::failed() const {
  std::lock_guard lock(m_mutex);
  return m_failed;
}

int64_t CheckpointWriter::superseded() const {
  std::lock_guard lock(m_mutex);
  return m_superseded;
}

}  // namespace rbsim
