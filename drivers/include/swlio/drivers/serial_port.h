#pragma once
/// @file
/// Serial-port I/O shell (the only driver code that touches termios).
///
/// Raw 8N1, no flow control, no echo or line processing (termios(3) `cfmakeraw`, CLOCAL |
/// CREAD), VMIN = VTIME = 0 with `poll(2)` for timeouts. Line rates 9600 … 921600 and, where
/// the port accepts them, 1000000 / 1500000 / 2000000 (Linux B-constants). When the device
/// disappears (read gives EOF/EIO, poll reports POLLHUP/POLLERR: a USB-serial adapter pulled,
/// a pty master closed) the port closes itself and `Read` re-opens the path every
/// `reopen_interval_ns` until it comes back. Each read is stamped with CLOCK_MONOTONIC ns
/// taken right after `read(2)` returns.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "swlio/drivers/rx_timestamp.h"  // MonotonicNowNs(): the host clock

namespace swlio::drivers {

struct SerialPortOptions {
  std::string device;                        ///< path, e.g. /dev/ttyUSB0 or a by-id symlink
  int64_t baud = 921600;                     ///< line rate, bit/s
  int64_t reopen_interval_ns = 200'000'000;  ///< wait between re-open attempts
};

enum class SerialReadStatus : uint8_t {
  kData,      ///< `bytes` > 0 bytes were read
  kTimeout,   ///< nothing arrived within the timeout
  kClosed,    ///< the device is absent (just vanished or not back yet); re-open is automatic
  kReopened,  ///< the device came back and was re-opened (re-run its configuration)
};

struct SerialRead {
  SerialReadStatus status = SerialReadStatus::kTimeout;
  size_t bytes = 0;
  int64_t t_host_ns = 0;  ///< CLOCK_MONOTONIC right after read(2)
};

struct SerialPortStats {
  uint64_t bytes_read = 0;
  uint64_t reads = 0;
  uint64_t opens = 0;          ///< successful opens (first open included)
  uint64_t open_failures = 0;  ///< failed open attempts
  uint64_t disconnects = 0;    ///< device vanished while open
  uint64_t bytes_written = 0;
  uint64_t write_failures = 0;
};

class SerialPort {
 public:
  explicit SerialPort(SerialPortOptions options);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  /// One open attempt: open, raw mode, line rate. False (with `last_error()`) on failure.
  bool Open();
  void Close();
  bool is_open() const { return fd_ >= 0; }

  /// Waits up to `timeout_ns` for bytes into `buf`. While the device is absent it tries to
  /// re-open (at most every reopen_interval_ns) and returns kClosed after waiting.
  SerialRead Read(std::span<uint8_t> buf, int64_t timeout_ns);

  /// Writes all of `data` within `timeout_ns`; false when closed, on error or timeout.
  bool Write(std::span<const uint8_t> data, int64_t timeout_ns);

  const std::string& last_error() const { return last_error_; }
  const SerialPortStats& stats() const { return stats_; }
  const SerialPortOptions& options() const { return options_; }

 private:
  void Disconnected(const char* why, int err);
  SerialRead WaitForReopen(int64_t timeout_ns);

  SerialPortOptions options_;
  int fd_ = -1;
  int64_t next_open_ns_ = 0;
  std::string last_error_;
  SerialPortStats stats_;
};

/// True when `baud` is a rate SerialPort can request (the port may still refuse it).
bool IsSupportedSerialBaud(int64_t baud);

}  // namespace swlio::drivers
