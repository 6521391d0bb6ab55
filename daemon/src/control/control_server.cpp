#include "swlio/daemon/control/control_server.h"

#include <grp.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "swlio/core/time.h"

namespace swlio::daemon {
namespace {

using control::Reply;
using control::ReplyStatus;

std::string Errno(const std::string& what) { return what + ": " + std::strerror(errno); }

int64_t ToNs(double s) { return static_cast<int64_t>(s * 1e9); }

bool MakeAddress(const std::string& path, sockaddr_un* addr) {
  *addr = sockaddr_un{};
  addr->sun_family = AF_UNIX;
  if (path.empty() || path.size() >= sizeof addr->sun_path) return false;
  std::memcpy(addr->sun_path, path.data(), path.size());
  return true;
}

/// A socket file left by a daemon that did not stop cleanly is removed; one that a running
/// daemon listens on, or any other file, is not. False with *error when the path is taken.
bool ClearStaleSocket(const sockaddr_un& addr, const std::string& path, std::string* error) {
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) return true;  // nothing there (or the bind will say)
  if (!S_ISSOCK(st.st_mode)) {
    *error = path + " exists and is not a socket";
    return false;
  }
  const int probe = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (probe < 0) {
    *error = Errno("socket");
    return false;
  }
  const bool live = connect(probe, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
  const int connect_errno = errno;
  close(probe);
  if (live) {
    *error = "another process (a second swliod?) listens on " + path;
    return false;
  }
  if (connect_errno != ECONNREFUSED) {
    *error = path + ": " + std::strerror(connect_errno);
    return false;
  }
  if (unlink(path.c_str()) != 0) {
    *error = Errno("removing the stale socket " + path);
    return false;
  }
  return true;
}

std::optional<gid_t> GroupId(const std::string& name) {
  group gr{};
  group* found = nullptr;
  std::array<char, 4096> buf{};
  if (getgrnam_r(name.c_str(), &gr, buf.data(), buf.size(), &found) != 0 || found == nullptr) {
    return std::nullopt;
  }
  return found->gr_gid;
}

/// Gives the socket file the operators' group; a warning when that is not possible.
std::optional<gid_t> ApplyGroup(const std::string& path,
                                const std::string& name,
                                std::string* warning) {
  if (name.empty()) return std::nullopt;
  const std::optional<gid_t> gid = GroupId(name);
  if (!gid) {
    *warning = "control.group '" + name +
               "' does not exist: the socket keeps the daemon's group, so only the daemon's "
               "user and that group can connect (systemd-sysusers creates it)";
    return std::nullopt;
  }
  struct stat st {};
  // Under swliod.service /run/swlio is set-group-ID and of this group already
  // (swlio.tmpfiles.conf), and chown(2) is not among the unit's allowed system calls.
  if (stat(path.c_str(), &st) == 0 && st.st_gid == *gid) return gid;
  if (chown(path.c_str(), static_cast<uid_t>(-1), *gid) != 0) {
    *warning = Errno("control.group '" + name + "': chown of " + path) +
               " (the daemon's user must be a member of the group); operators in that group "
               "cannot connect";
  }
  return gid;
}

}  // namespace

struct ControlServer::Connection {
  int fd = -1;
  std::string who;  ///< DescribePeer, for the log
  control::RequestReader reader;
  std::string request_text;  ///< the command as logged
  std::shared_ptr<PendingCommand> pending;
  std::string out;
  size_t written = 0;
  bool writing = false;
  /// The reply is out (SHUT_WR): what the client still sends is read and dropped until it
  /// closes, so that closing never resets the connection before the client read the reply.
  bool draining = false;
  size_t drained = 0;
  bool done = false;
  int64_t deadline_ns = 0;

  ~Connection() {
    if (fd >= 0) close(fd);
  }
};

std::unique_ptr<ControlServer> ControlServer::Listen(const ControlConfig& config,
                                                     ControlTarget* target,
                                                     std::string* error,
                                                     std::string* warning) {
  sockaddr_un addr{};
  if (!MakeAddress(config.socket, &addr)) {
    *error = "control.socket '" + config.socket + "' is empty or too long";
    return nullptr;
  }
  if (!ClearStaleSocket(addr, config.socket, error)) return nullptr;
  const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd < 0) {
    *error = Errno("socket");
    return nullptr;
  }
  auto fail = [&](const std::string& what, bool unlink_path) -> std::unique_ptr<ControlServer> {
    *error = Errno(what);
    close(fd);
    if (unlink_path) unlink(config.socket.c_str());
    return nullptr;
  };
  if (bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    return fail("bind " + config.socket, false);
  }
  // bind creates the file as 0777 & ~umask; connecting needs write permission.
  if (chmod(config.socket.c_str(), 0660) != 0) return fail("chmod " + config.socket, true);
  ControlAccess access;
  access.daemon_uid = geteuid();
  access.daemon_gid = getegid();
  access.operator_gid = ApplyGroup(config.socket, config.group, warning);
  if (listen(fd, 16) != 0) return fail("listen " + config.socket, true);
  return std::unique_ptr<ControlServer>(new ControlServer(config, target, fd, access));
}

ControlServer::ControlServer(const ControlConfig& config,
                             ControlTarget* target,
                             int fd,
                             ControlAccess access)
    : config_(config), target_(target), listen_fd_(fd), path_(config.socket), access_(access) {}

ControlServer::~ControlServer() {
  for (auto& c : connections_) {
    if (c->pending) c->pending->Cancel();
  }
  connections_.clear();
  close(listen_fd_);
  unlink(path_.c_str());
}

void ControlServer::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  std::vector<pollfd> fds;
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    fds.clear();
    fds.push_back({listen_fd_, POLLIN, 0});
    bool waiting = false;
    for (const auto& c : connections_) {
      const auto events = static_cast<short>(c->writing ? POLLOUT : c->pending ? 0 : POLLIN);
      waiting = waiting || c->pending != nullptr;
      fds.push_back({c->fd, events, 0});
    }
    // A pending command is polled every 10 ms; otherwise the stop flag every 100 ms.
    if (poll(fds.data(), fds.size(), waiting ? 10 : 100) < 0 && errno != EINTR) {
      spdlog::error("control: {}", Errno("poll"));
      return;
    }
    const int64_t now = MonotonicNowNs();
    const size_t known = connections_.size();  // Accept appends; they have no pollfd yet
    for (size_t i = 0; i < known; ++i) {
      Connection& c = *connections_[i];
      const short revents = fds[i + 1].revents;
      if (c.pending && (revents & (POLLHUP | POLLERR)) != 0) {
        // Nobody to answer; the command itself runs to its end (its result is in the log).
        spdlog::info("control: {} from {}: the client went away; the command goes on",
                     c.request_text, c.who);
        c.done = true;
      } else if (c.pending) {
        Poll(c, now);
      } else if (c.writing) {
        if (revents != 0 || now > c.deadline_ns) c.done = Write(c, now);
      } else if (c.draining) {
        if (revents != 0 || now > c.deadline_ns) c.done = Drain(c, now);
      } else if (revents != 0) {
        Read(c, now);
      } else if (now > c.deadline_ns) {
        bad_requests_.fetch_add(1, std::memory_order_relaxed);
        spdlog::warn("control: {} sent no complete request within {} s; dropped", c.who,
                     config_.request_timeout_s);
        Respond(c, {ReplyStatus::kBadRequest, "no complete request line in time", ""}, now);
      }
    }
    if (fds[0].revents != 0) Accept(now);
    std::erase_if(connections_, [](const auto& c) { return c->done; });
  }
}

void ControlServer::Accept(int64_t now_ns) {
  for (int i = 0; i < 16; ++i) {  // a burst of clients; the rest on the next round
    const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) {
      if (errno != EAGAIN && errno != EINTR && errno != ECONNABORTED)
        spdlog::warn("control: {}", Errno("accept"));
      return;
    }
    connections_count_.fetch_add(1, std::memory_order_relaxed);
    auto c = std::make_unique<Connection>();
    c->fd = fd;
    c->deadline_ns = now_ns + ToNs(config_.request_timeout_s);
    const std::optional<PeerCredentials> peer = ReadPeerCredentials(fd);
    c->who = peer ? DescribePeer(*peer) : "an unknown peer";
    Connection& ref = *c;
    connections_.push_back(std::move(c));
    if (!peer || !PeerAllowed(*peer, access_)) {
      refused_peers_.fetch_add(1, std::memory_order_relaxed);
      spdlog::warn("control: refused {}: not the daemon's user nor in its groups", ref.who);
      Respond(ref, {ReplyStatus::kRefused, "not allowed: not the daemon's user or group", ""},
              now_ns);
    } else if (connections_.size() > static_cast<size_t>(config_.max_clients)) {
      busy_.fetch_add(1, std::memory_order_relaxed);
      Respond(ref, {ReplyStatus::kBusy, "too many clients at once; try again", ""}, now_ns);
    }
  }
}

void ControlServer::Read(Connection& c, int64_t now_ns) {
  char buf[1024];
  while (c.reader.state() == control::RequestReader::State::kIncomplete) {
    const ssize_t n = recv(c.fd, buf, sizeof buf, 0);
    if (n > 0) {
      c.reader.Add(std::string_view(buf, static_cast<size_t>(n)));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) return;  // more later
    // EOF or an error before the line ended: nobody to answer.
    bad_requests_.fetch_add(1, std::memory_order_relaxed);
    spdlog::debug("control: {} closed without a complete request", c.who);
    c.done = true;
    return;
  }
  if (c.reader.state() == control::RequestReader::State::kError) {
    bad_requests_.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("control: bad request from {}: {}", c.who, c.reader.error());
    Respond(c, {ReplyStatus::kBadRequest, c.reader.error(), ""}, now_ns);
    return;
  }
  Handle(c, now_ns);
}

void ControlServer::Handle(Connection& c, int64_t now_ns) {
  std::string error;
  const std::optional<control::Request> request = control::ParseRequest(c.reader.line(), &error);
  if (!request) {
    bad_requests_.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("control: bad request from {}: {}", c.who, error);
    Respond(c, {ReplyStatus::kBadRequest, error, ""}, now_ns);
    return;
  }
  commands_.fetch_add(1, std::memory_order_relaxed);
  c.request_text = control::ToString(request->command);
  if (!request->argument.empty()) c.request_text += " " + request->argument;
  if (request->command == control::Command::kStatus) {
    spdlog::debug("control: status from {}", c.who);  // scripts may poll it every second
    Respond(c, {ReplyStatus::kOk, "", target_->Status()}, now_ns);
    return;
  }
  spdlog::info("control: {} from {}", c.request_text, c.who);
  Reply refusal;
  c.pending = target_->Submit(*request, &refusal);
  if (!c.pending) {
    spdlog::warn("control: {} from {}: {}: {}", c.request_text, c.who,
                 control::ToString(refusal.status), refusal.message);
    Respond(c, refusal, now_ns);
    return;
  }
  c.deadline_ns = now_ns + ToNs(config_.command_timeout_s);
}

void ControlServer::Poll(Connection& c, int64_t now_ns) {
  if (std::optional<Reply> reply = c.pending->Result()) {
    if (reply->status == ReplyStatus::kOk) {
      spdlog::info("control: {} from {}: ok {}", c.request_text, c.who, reply->message);
    } else {
      spdlog::warn("control: {} from {}: {}: {}", c.request_text, c.who,
                   control::ToString(reply->status), reply->message);
    }
    Respond(c, *reply, now_ns);
    return;
  }
  if (now_ns <= c.deadline_ns) return;
  c.pending->Cancel();
  timeouts_.fetch_add(1, std::memory_order_relaxed);
  char message[160];
  std::snprintf(message, sizeof message,
                "not finished within control.command_timeout_s (%.1f s); it may still complete: "
                "see the daemon's log",
                config_.command_timeout_s);
  spdlog::warn("control: {} from {}: {}", c.request_text, c.who, message);
  Respond(c, {ReplyStatus::kTimeout, message, ""}, now_ns);
}

void ControlServer::Respond(Connection& c, const Reply& reply, int64_t now_ns) {
  c.pending.reset();
  c.out = control::FormatReply(reply);
  c.written = 0;
  c.writing = true;
  c.deadline_ns = now_ns + ToNs(config_.request_timeout_s);
  c.done = Write(c, now_ns);
}

bool ControlServer::Drain(Connection& c, int64_t now_ns) {
  char buf[1024];
  for (;;) {
    const ssize_t n = recv(c.fd, buf, sizeof buf, 0);
    if (n > 0) {
      c.drained += static_cast<size_t>(n);
      if (c.drained > 16 * control::kMaxRequestBytes) return true;  // enough politeness
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) return now_ns > c.deadline_ns;
    return true;  // the client closed
  }
}

bool ControlServer::Write(Connection& c, int64_t now_ns) {
  while (c.written < c.out.size()) {
    const ssize_t n = send(c.fd, c.out.data() + c.written, c.out.size() - c.written, MSG_NOSIGNAL);
    if (n > 0) {
      c.written += static_cast<size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else if (n < 0 && errno == EAGAIN) {
      if (now_ns <= c.deadline_ns) return false;  // the rest when the client reads
      spdlog::warn("control: {} did not read its reply in time; dropped", c.who);
      return true;
    } else {
      return true;  // the client went away
    }
  }
  shutdown(c.fd, SHUT_WR);
  c.writing = false;
  c.draining = true;
  return false;
}

ControlCounters ControlServer::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  ControlCounters c;
  c.enabled = true;
  c.connections = connections_count_.load(kRelaxed);
  c.commands = commands_.load(kRelaxed);
  c.bad_requests = bad_requests_.load(kRelaxed);
  c.refused_peers = refused_peers_.load(kRelaxed);
  c.busy = busy_.load(kRelaxed);
  c.timeouts = timeouts_.load(kRelaxed);
  return c;
}

}  // namespace swlio::daemon
