// Serial-port I/O shell: termios raw mode, poll-based reads, automatic re-open. See
// serial_port.h; termios(3), poll(2) and tty_ioctl(4) are the references.

#include "swlio/drivers/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <optional>
#include <utility>

namespace swlio::drivers {
namespace {

struct BaudEntry {
  int64_t baud;
  speed_t speed;
};
constexpr std::array<BaudEntry, 12> kBauds = {{{9600, B9600},
                                               {19200, B19200},
                                               {38400, B38400},
                                               {57600, B57600},
                                               {115200, B115200},
                                               {230400, B230400},
                                               {460800, B460800},
                                               {500000, B500000},
                                               {921600, B921600},
                                               {1000000, B1000000},
                                               {1500000, B1500000},
                                               {2000000, B2000000}}};

std::optional<speed_t> SpeedFor(int64_t baud) {
  for (const BaudEntry& e : kBauds) {
    if (e.baud == baud) return e.speed;
  }
  return std::nullopt;
}

int PollTimeoutMs(int64_t timeout_ns) {
  if (timeout_ns <= 0) return 0;
  const int64_t ms = (timeout_ns + 999'999) / 1'000'000;  // round up: never spin
  return static_cast<int>(std::min<int64_t>(ms, 1'000'000));
}

std::string Errno(const char* what, int err) {
  return std::string(what) + ": " + std::strerror(err);
}

}  // namespace

bool IsSupportedSerialBaud(int64_t baud) { return SpeedFor(baud).has_value(); }

SerialPort::SerialPort(SerialPortOptions options) : options_(std::move(options)) {}

SerialPort::~SerialPort() { Close(); }

void SerialPort::Close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool SerialPort::Open() {
  Close();
  const std::optional<speed_t> speed = SpeedFor(options_.baud);
  if (!speed) {
    last_error_ = "unsupported baud rate " + std::to_string(options_.baud);
    ++stats_.open_failures;
    return false;
  }
  const int fd = ::open(options_.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    last_error_ = Errno(("open " + options_.device).c_str(), errno);
    ++stats_.open_failures;
    return false;
  }
  termios tio{};
  bool ok = ::tcgetattr(fd, &tio) == 0;
  if (ok) {
    ::cfmakeraw(&tio);
    tio.c_cflag |= CLOCAL | CREAD;
    tio.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | PARENB | CRTSCTS);
    tio.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    ok = ::cfsetispeed(&tio, *speed) == 0 && ::cfsetospeed(&tio, *speed) == 0 &&
         ::tcsetattr(fd, TCSANOW, &tio) == 0;
  }
  if (!ok) {
    last_error_ = Errno(("termios " + options_.device).c_str(), errno);
    ::close(fd);
    ++stats_.open_failures;
    return false;
  }
  ::ioctl(fd, TIOCEXCL);     // best effort: keep other programs off the port
  ::tcflush(fd, TCIOFLUSH);  // drop bytes queued before we were ready
  fd_ = fd;
  ++stats_.opens;
  last_error_.clear();
  return true;
}

void SerialPort::Disconnected(const char* why, int err) {
  last_error_ = err != 0 ? Errno(why, err) : std::string(why);
  Close();
  ++stats_.disconnects;
  next_open_ns_ = MonotonicNowNs();  // the device may already be back
}

SerialRead SerialPort::WaitForReopen(int64_t timeout_ns) {
  const int64_t now = MonotonicNowNs();
  if (now >= next_open_ns_) {
    if (Open()) return {SerialReadStatus::kReopened, 0, now};
    next_open_ns_ = now + options_.reopen_interval_ns;
  }
  const int64_t wait_ns = std::min(timeout_ns, next_open_ns_ - now);
  if (wait_ns > 0) {
    const timespec ts{static_cast<time_t>(wait_ns / 1'000'000'000),
                      static_cast<long>(wait_ns % 1'000'000'000)};
    ::nanosleep(&ts, nullptr);
  }
  return {SerialReadStatus::kClosed, 0, MonotonicNowNs()};
}

SerialRead SerialPort::Read(std::span<uint8_t> buf, int64_t timeout_ns) {
  if (fd_ < 0) return WaitForReopen(timeout_ns);
  pollfd pfd{fd_, POLLIN, 0};
  const int r = ::poll(&pfd, 1, PollTimeoutMs(timeout_ns));
  if (r < 0) {
    if (errno == EINTR) return {SerialReadStatus::kTimeout, 0, MonotonicNowNs()};
    Disconnected("poll", errno);
    return {SerialReadStatus::kClosed, 0, MonotonicNowNs()};
  }
  if (r == 0) return {SerialReadStatus::kTimeout, 0, MonotonicNowNs()};
  if ((pfd.revents & POLLIN) != 0) {
    const ssize_t n = ::read(fd_, buf.data(), buf.size());
    const int64_t t = MonotonicNowNs();
    if (n > 0) {
      ++stats_.reads;
      stats_.bytes_read += static_cast<uint64_t>(n);
      return {SerialReadStatus::kData, static_cast<size_t>(n), t};
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return {SerialReadStatus::kTimeout, 0, t};
    Disconnected(n == 0 ? "end of file" : "read", n == 0 ? 0 : errno);
    return {SerialReadStatus::kClosed, 0, t};
  }
  // POLLHUP / POLLERR / POLLNVAL without data: the device is gone.
  Disconnected("device hung up", 0);
  return {SerialReadStatus::kClosed, 0, MonotonicNowNs()};
}

bool SerialPort::Write(std::span<const uint8_t> data, int64_t timeout_ns) {
  const int64_t deadline = MonotonicNowNs() + timeout_ns;
  size_t done = 0;
  while (fd_ >= 0 && done < data.size()) {
    const ssize_t n = ::write(fd_, data.data() + done, data.size() - done);
    if (n > 0) {
      done += static_cast<size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) {
      Disconnected("write", errno);
      break;
    }
    const int64_t left = deadline - MonotonicNowNs();
    if (left <= 0) break;
    pollfd pfd{fd_, POLLOUT, 0};
    ::poll(&pfd, 1, PollTimeoutMs(left));
  }
  stats_.bytes_written += done;
  if (done < data.size()) ++stats_.write_failures;
  return done == data.size();
}

}  // namespace swlio::drivers
