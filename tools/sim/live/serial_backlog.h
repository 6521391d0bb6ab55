#pragma once
/// @file
/// The simulator's side of a USB-serial adapter. Bytes the host has not read yet wait in the
/// kernel's tty flip buffer, which for a real adapter (ftdi_sio, cdc_acm) holds up to
/// TTYB_DEFAULT_MEM_LIMIT = 640 KiB (Linux drivers/tty/tty_buffer.c), about 27 s of MTi data
/// at 400 Hz. A pseudo-terminal's is limited to 8 KiB (drivers/tty/pty.c, tty_buffer_set_limit):
/// with the line discipline's 4 KiB it takes about 20 KB (measured here), under a second of
/// IMU data, after which a write fails. So that the test harness is no less tolerant than the
/// adapter it stands for, what the pty cannot take yet waits here, in order, up to the real
/// adapter's limit, and goes out as soon as the pty has room. Only beyond that limit are bytes
/// dropped, and counted, as a real adapter drops them.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

namespace swlio::sim {

struct SerialBacklogStats {
  uint64_t written = 0;     ///< bytes the pty took
  uint64_t dropped = 0;     ///< bytes beyond the adapter's limit, lost
  uint64_t delayed = 0;     ///< bytes that had to wait here for room in the pty
  size_t max_backlog = 0;   ///< the most bytes waiting here at once
  int64_t max_wait_ns = 0;  ///< the longest a byte waited here
};

class SerialBacklog {
 public:
  /// 640 KiB: Linux's TTYB_DEFAULT_MEM_LIMIT for a real serial port's flip buffer.
  static constexpr size_t kAdapterLimitBytes = size_t{640} * 1024;

  explicit SerialBacklog(size_t limit_bytes = kAdapterLimitBytes) : limit_(limit_bytes) {}

  /// Queues `bytes` (the frames of samples [first_sample, end_sample)) behind what waits, then
  /// writes what the non-blocking `fd` takes. Whole chunks beyond the limit are dropped.
  void Send(int fd,
            std::span<const uint8_t> bytes,
            size_t first_sample,
            size_t end_sample,
            int64_t now_ns);
  /// Writes what waits, as far as `fd` takes it.
  void Flush(int fd, int64_t now_ns);
  /// Drops everything waiting (the adapter was unplugged: its buffer went with it).
  void Clear() {
    chunks_.clear();
    bytes_ = 0;
  }
  bool empty() const { return chunks_.empty(); }
  /// While held, nothing is written: bytes only queue (LiveFaults::serial_stalls).
  void Hold(bool held) { held_ = held; }
  bool held() const { return held_; }
  const SerialBacklogStats& stats() const { return stats_; }
  /// Receives, per IMU sample index, the time its frame's last byte went into the pty.
  void ReportWritesTo(std::vector<int64_t>* write_ns) { write_ns_ = write_ns; }

 private:
  struct Chunk {
    std::vector<uint8_t> bytes;
    size_t offset = 0;  ///< bytes already written
    size_t first_sample = 0, end_sample = 0;
    int64_t queued_ns = 0;
  };
  void Complete(const Chunk& c, int64_t now_ns);

  size_t limit_;
  size_t bytes_ = 0;  ///< waiting
  std::deque<Chunk> chunks_;
  SerialBacklogStats stats_;
  std::vector<int64_t>* write_ns_ = nullptr;
  bool held_ = false;
};

}  // namespace swlio::sim
