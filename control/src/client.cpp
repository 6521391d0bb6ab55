#include "swlio/control/client.h"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

namespace swlio::control {
namespace {

using Clock = std::chrono::steady_clock;

class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

CallResult Failure(CallError error, std::string detail) {
  CallResult r;
  r.error = error;
  r.detail = std::move(detail);
  return r;
}

CallResult ConnectFailure(const std::string& path, int err) {
  const std::string what = path + ": " + std::strerror(err);
  if (err == ENOENT || err == ECONNREFUSED) {
    return Failure(CallError::kNoDaemon, what + " (is swliod running with control.socket set?)");
  }
  if (err == EACCES || err == EPERM) {
    return Failure(CallError::kPermission,
                   what + " (the socket is for the daemon's user and its control group)");
  }
  return Failure(CallError::kIo, what);
}

/// Milliseconds left until `deadline` (0 once passed).
int LeftMs(Clock::time_point deadline) {
  const auto left =
      std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left > 0 ? static_cast<int>(left) : 0;
}

/// Waits for `events` on fd; false on timeout.
bool WaitFor(int fd, short events, Clock::time_point deadline) {
  pollfd p{fd, events, 0};
  for (;;) {
    const int n = poll(&p, 1, LeftMs(deadline));
    if (n > 0) return true;
    if (n == 0) return false;
    if (errno != EINTR) return false;
  }
}

}  // namespace

CallResult Call(const std::string& socket_path, const Request& request, int timeout_ms) {
  const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  if (socket_path.empty() || socket_path.size() >= sizeof addr.sun_path) {
    return Failure(CallError::kIo, "socket path '" + socket_path + "' is empty or longer than " +
                                       std::to_string(sizeof addr.sun_path - 1) + " bytes");
  }
  std::memcpy(addr.sun_path, socket_path.data(), socket_path.size());
  const Fd fd(socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0));
  if (fd.get() < 0) return Failure(CallError::kIo, std::string("socket: ") + std::strerror(errno));
  // A UNIX stream connect completes at once or fails; EAGAIN: the listen backlog is full.
  while (connect(fd.get(), reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    if (errno == EINTR) continue;
    if (errno != EAGAIN) return ConnectFailure(socket_path, errno);
    if (LeftMs(deadline) == 0) return Failure(CallError::kTimeout, "the daemon's backlog is full");
    usleep(10'000);
  }
  const std::string line = FormatRequest(request);
  size_t sent = 0;
  while (sent < line.size()) {
    const ssize_t n = send(fd.get(), line.data() + sent, line.size() - sent, MSG_NOSIGNAL);
    if (n > 0) {
      sent += static_cast<size_t>(n);
    } else if (n < 0 && errno == EAGAIN) {
      if (!WaitFor(fd.get(), POLLOUT, deadline))
        return Failure(CallError::kTimeout, "the daemon did not take the request in time");
    } else if (n < 0 && (errno == EPIPE || errno == ECONNRESET)) {
      break;  // the daemon answered early (busy, refused) and closed: read that answer
    } else if (n < 0 && errno != EINTR) {
      return Failure(CallError::kIo, std::string("send: ") + std::strerror(errno));
    }
  }
  shutdown(fd.get(), SHUT_WR);  // the request is complete
  std::string text;
  char buf[4096];
  for (;;) {
    const ssize_t n = recv(fd.get(), buf, sizeof buf, 0);
    if (n > 0) {
      text.append(buf, static_cast<size_t>(n));
      if (text.size() > kMaxReplyBytes) return Failure(CallError::kProtocol, "reply too large");
    } else if (n == 0) {
      break;
    } else if (errno == EAGAIN) {
      if (!WaitFor(fd.get(), POLLIN, deadline)) {
        return Failure(CallError::kTimeout,
                       "no reply within " + std::to_string(timeout_ms) + " ms");
      }
    } else if (errno != EINTR) {
      return Failure(CallError::kIo, std::string("recv: ") + std::strerror(errno));
    }
  }
  std::string error;
  std::optional<Reply> reply = ParseReply(text, &error);
  if (!reply) return Failure(CallError::kProtocol, error);
  CallResult r;
  r.reply = std::move(*reply);
  return r;
}

}  // namespace swlio::control
