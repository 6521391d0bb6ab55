#include "live/serial_backlog.h"

#include <unistd.h>

#include <algorithm>

namespace swlio::sim {

void SerialBacklog::Send(int fd,
                         std::span<const uint8_t> bytes,
                         size_t first_sample,
                         size_t end_sample,
                         int64_t now_ns) {
  if (bytes.empty()) return;
  if (bytes_ + bytes.size() > limit_) {  // the adapter's buffer is full: these frames are lost
    stats_.dropped += bytes.size();
    return;
  }
  chunks_.push_back({{bytes.begin(), bytes.end()}, 0, first_sample, end_sample, now_ns});
  bytes_ += bytes.size();
  const bool waited = chunks_.size() > 1;
  Flush(fd, now_ns);
  if (waited || !chunks_.empty()) stats_.delayed += bytes.size();
  stats_.max_backlog = std::max(stats_.max_backlog, bytes_);
}

void SerialBacklog::Flush(int fd, int64_t now_ns) {
  while (!chunks_.empty() && fd >= 0 && !held_) {
    Chunk& c = chunks_.front();
    const ssize_t n = write(fd, c.bytes.data() + c.offset, c.bytes.size() - c.offset);
    if (n <= 0) return;  // full (EAGAIN) or gone: the bytes wait, in order
    c.offset += static_cast<size_t>(n);
    bytes_ -= static_cast<size_t>(n);
    stats_.written += static_cast<uint64_t>(n);
    if (c.offset < c.bytes.size()) return;
    Complete(c, now_ns);
    chunks_.pop_front();
  }
}

void SerialBacklog::Complete(const Chunk& c, int64_t now_ns) {
  stats_.max_wait_ns = std::max(stats_.max_wait_ns, now_ns - c.queued_ns);
  if (write_ns_ == nullptr) return;
  if (write_ns_->size() < c.end_sample) write_ns_->resize(c.end_sample, 0);
  std::fill(write_ns_->begin() + static_cast<std::ptrdiff_t>(c.first_sample),
            write_ns_->begin() + static_cast<std::ptrdiff_t>(c.end_sample), now_ns);
}

}  // namespace swlio::sim
