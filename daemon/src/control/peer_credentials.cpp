#include "swlio/daemon/control/peer_credentials.h"

#include <pwd.h>
#include <sys/socket.h>

#include <algorithm>
#include <array>

namespace swlio::daemon {

std::optional<PeerCredentials> ReadPeerCredentials(int fd) {
  ucred cred{};
  socklen_t len = sizeof cred;
  if (getsockopt(fd, SOL_SOCKET, SO_PEERCRED, &cred, &len) != 0 || len != sizeof cred) {
    return std::nullopt;
  }
  PeerCredentials peer;
  peer.pid = cred.pid;
  peer.uid = cred.uid;
  peer.gid = cred.gid;
  // A user is in at most NGROUPS_MAX (65536) groups; 256 covers any real operator, and a
  // larger list (ERANGE) leaves the supplementary groups unknown rather than half read.
  std::array<gid_t, 256> groups{};
  socklen_t bytes = sizeof groups;
  if (getsockopt(fd, SOL_SOCKET, SO_PEERGROUPS, groups.data(), &bytes) == 0) {
    peer.groups.assign(groups.begin(), groups.begin() + bytes / sizeof(gid_t));
    peer.groups_known = true;
  }
  return peer;
}

bool PeerAllowed(const PeerCredentials& peer, const ControlAccess& access) {
  if (peer.uid == 0 || peer.uid == access.daemon_uid) return true;
  auto member = [&peer](gid_t g) {
    return peer.gid == g ||
           std::find(peer.groups.begin(), peer.groups.end(), g) != peer.groups.end();
  };
  return member(access.daemon_gid) || (access.operator_gid && member(*access.operator_gid));
}

std::string DescribePeer(const PeerCredentials& peer) {
  std::string out = std::string("uid ").append(std::to_string(peer.uid));
  passwd pw{};
  passwd* found = nullptr;
  std::array<char, 1024> buf{};
  if (getpwuid_r(peer.uid, &pw, buf.data(), buf.size(), &found) == 0 && found != nullptr) {
    out.append(" (").append(found->pw_name).append(")");
  }
  return out + " pid " + std::to_string(peer.pid);
}

}  // namespace swlio::daemon
