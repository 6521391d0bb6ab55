#pragma once
/// @file
/// The control thread (docs/control.md): swliod's side of swlioctl. It listens on a UNIX stream
/// socket (control.socket, mode 0660, group control.group), and serves one request line per
/// connection (swlio/control/protocol.h), several connections at once from one poll(2) loop:
///
///   accept ──► read the line (≤ 4 KiB, within request_timeout_s) ──► parse
///     status           answered at once (ControlTarget::Status)
///     save-map, reset  handed to the owning thread (ControlTarget::Submit); the reply waits
///                      for its PendingCommand, at most command_timeout_s, without blocking
///                      the loop
///   ──► write the reply (within request_timeout_s) ──► shut down the sending side, drain what
///       the client still sends until it closes (within request_timeout_s) ──► close
///
/// A peer the credentials check refuses, a client that sends garbage, too much, or nothing
/// in time, gets an error line (when it can take one) and is closed; nothing a client does
/// blocks the loop or another thread. Each command is logged with who issued it.

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "swlio/control/protocol.h"
#include "swlio/daemon/config/daemon_config.h"
#include "swlio/daemon/control/peer_credentials.h"
#include "swlio/daemon/control/pending_command.h"
#include "swlio/daemon/runtime/watchdog.h"

namespace swlio::daemon {

/// What the control thread acts on (the Runtime; a fake in tests). Called on the control
/// thread only.
class ControlTarget {
 public:
  virtual ~ControlTarget() = default;
  /// The status reply's body (lines).
  virtual std::string Status() = 0;
  /// Hands save-map or reset to the thread that executes it: the pending command, or null
  /// with *refusal filled (refused: not possible in this configuration; busy: queue full).
  virtual std::shared_ptr<PendingCommand> Submit(const control::Request& request,
                                                 control::Reply* refusal) = 0;
};

struct ControlCounters {
  bool enabled = false;
  uint64_t connections = 0;
  uint64_t commands = 0;       ///< requests that parsed and were allowed
  uint64_t bad_requests = 0;   ///< garbage, oversize, nothing in time
  uint64_t refused_peers = 0;  ///< by the credentials check
  uint64_t busy = 0;           ///< connections over max_clients
  uint64_t timeouts = 0;       ///< commands not finished within command_timeout_s
};

class ControlServer {
 public:
  /// Creates the socket at config.socket (replacing a stale one nobody listens on), mode 0660,
  /// group config.group. Null with *error when it cannot (the caller logs it and runs on);
  /// *warning set when it listens but the group could not be applied.
  static std::unique_ptr<ControlServer> Listen(const ControlConfig& config,
                                               ControlTarget* target,
                                               std::string* error,
                                               std::string* warning);
  /// Closes the socket and removes its file.
  ~ControlServer();
  ControlServer(const ControlServer&) = delete;
  ControlServer& operator=(const ControlServer&) = delete;

  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  const std::string& path() const { return path_; }
  /// Relaxed copies (any thread).
  ControlCounters counters() const;

 private:
  struct Connection;
  ControlServer(const ControlConfig& config, ControlTarget* target, int fd, ControlAccess access);
  void Accept(int64_t now_ns);
  /// Reads what arrived; on a complete line, handles it.
  void Read(Connection& c, int64_t now_ns);
  void Handle(Connection& c, int64_t now_ns);
  /// A pending command finished or timed out: its reply.
  void Poll(Connection& c, int64_t now_ns);
  void Respond(Connection& c, const control::Reply& reply, int64_t now_ns);
  /// Writes what it can; once all is written, shuts down the sending side and drains. True
  /// when the connection is done (it failed, or did not read in time).
  bool Write(Connection& c, int64_t now_ns);
  /// Reads and drops what the client still sends; true once it closed (or the deadline, or too
  /// much).
  bool Drain(Connection& c, int64_t now_ns);

  ControlConfig config_;
  ControlTarget* target_;
  int listen_fd_;
  std::string path_;
  ControlAccess access_;
  std::vector<std::unique_ptr<Connection>> connections_;
  std::atomic<uint64_t> connections_count_{0}, commands_{0}, bad_requests_{0}, refused_peers_{0},
      busy_{0}, timeouts_{0};
};

}  // namespace swlio::daemon
