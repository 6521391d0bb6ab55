#pragma once
/// @file
/// Who is at the other end of a control connection (SO_PEERCRED, SO_PEERGROUPS), and whether
/// the daemon serves them. The socket's permissions (0660, the daemon's user and
/// control.group) already keep everyone else out; this second check holds even when the file's
/// mode or group were changed by hand, and names the peer in the log.

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace swlio::daemon {

struct PeerCredentials {
  pid_t pid = 0;
  uid_t uid = 0;
  gid_t gid = 0;              ///< primary group
  std::vector<gid_t> groups;  ///< supplementary groups (SO_PEERGROUPS)
  bool groups_known = false;  ///< false: the kernel has no SO_PEERGROUPS (before Linux 4.13)
};

/// Who may talk to the daemon: root, the daemon's own user, and members (primary or
/// supplementary) of the daemon's group or of control.group.
struct ControlAccess {
  uid_t daemon_uid = 0;
  gid_t daemon_gid = 0;
  std::optional<gid_t> operator_gid;  ///< control.group, when it names an existing group
};

/// The credentials of the peer of a connected UNIX socket; std::nullopt when the kernel does
/// not say (then the connection is refused).
std::optional<PeerCredentials> ReadPeerCredentials(int fd);

bool PeerAllowed(const PeerCredentials& peer, const ControlAccess& access);

/// "uid 1000 (alice) pid 4242" for the log (the name when the user database has one).
std::string DescribePeer(const PeerCredentials& peer);

}  // namespace swlio::daemon
