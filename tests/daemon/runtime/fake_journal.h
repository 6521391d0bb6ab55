#pragma once
// A journald stand-in for tests: runs a function in a forked child whose own mount namespace has
// a tmpfs on /run with a datagram socket bound at /run/systemd/journal/socket, the fixed path
// sd_journal_sendv(3) sends to, and hands back the datagrams it received. Needs root, or
// unprivileged user namespaces (the child then maps its uid to root in one); otherwise the
// result says why it was skipped. Also a parser of the native journal protocol
// (https://systemd.io/JOURNAL_NATIVE_PROTOCOL/).

#include <fcntl.h>
#include <sched.h>
#include <sys/mount.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace swlio::daemon::test {

struct FakeJournalRun {
  std::string skipped;  ///< why no namespace could be made; empty when it ran
  std::string error;    ///< a set-up failure in the child
  std::vector<std::string> datagrams;
};

/// One journal entry: field name → values (a field may repeat).
using JournalEntry = std::multimap<std::string, std::string>;

/// Parses one native-protocol datagram. Each field is either `NAME=value\n`, or, for values
/// holding newlines or binary data, `NAME\n` + the value's size as a little-endian 64-bit
/// integer + the value + `\n` (systemd.io/JOURNAL_NATIVE_PROTOCOL). nullopt when malformed.
inline std::optional<JournalEntry> ParseJournalDatagram(std::string_view d) {
  JournalEntry entry;
  while (!d.empty()) {
    const size_t nl = d.find('\n');
    if (nl == std::string_view::npos) return std::nullopt;
    const std::string_view line = d.substr(0, nl);
    const size_t eq = line.find('=');
    if (eq != std::string_view::npos) {
      entry.emplace(std::string(line.substr(0, eq)), std::string(line.substr(eq + 1)));
      d.remove_prefix(nl + 1);
      continue;
    }
    d.remove_prefix(nl + 1);
    if (d.size() < 8) return std::nullopt;
    uint64_t size = 0;
    for (int i = 7; i >= 0; --i) size = (size << 8) | static_cast<unsigned char>(d[i]);
    d.remove_prefix(8);
    if (d.size() < size + 1 || d[size] != '\n') return std::nullopt;
    entry.emplace(std::string(line), std::string(d.substr(0, size)));
    d.remove_prefix(size + 1);
  }
  return entry;
}

namespace fake_journal_detail {

inline bool WriteAll(int fd, const void* data, size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t w = write(fd, p, n);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) return false;
    p += w;
    n -= static_cast<size_t>(w);
  }
  return true;
}

/// Child → parent records: a kind byte ('S' skipped, 'E' error, 'D' datagram), a 32-bit size,
/// the bytes.
inline void Send(int fd, char kind, const std::string& bytes) {
  const auto size = static_cast<uint32_t>(bytes.size());
  WriteAll(fd, &kind, 1);
  WriteAll(fd, &size, sizeof size);
  WriteAll(fd, bytes.data(), bytes.size());
}

inline bool WriteFile(const char* path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  out.flush();
  return static_cast<bool>(out);
}

/// A private mount namespace: as root, or else inside a new user namespace mapping our uid to
/// root. Empty on success, else why not.
inline std::string EnterMountNamespace() {
  if (unshare(CLONE_NEWNS) == 0) return {};
  const int first = errno;
  const uid_t uid = getuid();
  const gid_t gid = getgid();
  if (unshare(CLONE_NEWUSER | CLONE_NEWNS) != 0) {
    return std::string("unshare(CLONE_NEWNS): ") + std::strerror(first) +
           "; unshare(CLONE_NEWUSER | CLONE_NEWNS): " + std::strerror(errno);
  }
  if (!WriteFile("/proc/self/setgroups", "deny") ||
      !WriteFile("/proc/self/uid_map", "0 " + std::to_string(uid) + " 1\n") ||
      !WriteFile("/proc/self/gid_map", "0 " + std::to_string(gid) + " 1\n")) {
    return "cannot write the user namespace's uid/gid maps";
  }
  return {};
}

inline void RunChild(int out, const std::function<void()>& body) {
  if (const std::string why = EnterMountNamespace(); !why.empty()) {
    Send(out, 'S', why);
    return;
  }
  // Private propagation first, so that the tmpfs stays in this namespace.
  if (mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
      mount("tmpfs", "/run", "tmpfs", 0, "mode=0755") != 0) {
    Send(out, 'S', std::string("mount in a private namespace: ") + std::strerror(errno));
    return;
  }
  if (mkdir("/run/systemd", 0755) != 0 || mkdir("/run/systemd/journal", 0755) != 0) {
    Send(out, 'E', std::string("mkdir: ") + std::strerror(errno));
    return;
  }
  const int sock = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, "/run/systemd/journal/socket", sizeof addr.sun_path - 1);
  if (sock < 0 || bind(sock, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    Send(out, 'E', std::string("journal socket: ") + std::strerror(errno));
    return;
  }
  body();  // unix datagrams are queued on the receiver before sendmsg returns
  std::string buffer(256 * 1024, '\0');
  for (;;) {
    const ssize_t n = recv(sock, buffer.data(), buffer.size(), MSG_DONTWAIT);
    if (n < 0) break;
    Send(out, 'D', buffer.substr(0, static_cast<size_t>(n)));
  }
}

inline bool ReadAll(int fd, void* data, size_t n) {
  char* p = static_cast<char*>(data);
  while (n > 0) {
    const ssize_t r = read(fd, p, n);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) return false;
    p += r;
    n -= static_cast<size_t>(r);
  }
  return true;
}

}  // namespace fake_journal_detail

/// Runs `body` in a forked child with the fake journal; the datagrams it sent there.
inline FakeJournalRun RunWithFakeJournal(const std::function<void()>& body) {
  namespace d = fake_journal_detail;
  FakeJournalRun run;
  int fds[2];
  if (pipe(fds) != 0) {
    run.error = "pipe failed";
    return run;
  }
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    d::RunChild(fds[1], body);
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  char kind = 0;
  uint32_t size = 0;
  while (d::ReadAll(fds[0], &kind, 1) && d::ReadAll(fds[0], &size, sizeof size)) {
    std::string bytes(size, '\0');
    if (size > 0 && !d::ReadAll(fds[0], bytes.data(), size)) break;
    if (kind == 'S') run.skipped = bytes;
    if (kind == 'E') run.error = bytes;
    if (kind == 'D') run.datagrams.push_back(std::move(bytes));
  }
  close(fds[0]);
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) != pid || !WIFEXITED(status) ||
      WEXITSTATUS(status) != 0) {
    run.error += " (the child did not exit cleanly)";
  }
  return run;
}

}  // namespace swlio::daemon::test
