// The control thread (control_server.h) against a fake target: what a client gets for
// garbage, too much, or nothing; that no client blocks another; commands that wait for
// their owning thread, time out, or exceed max_clients; the socket's permissions and the peer
// credentials check (as root: a child that dropped to `nobody` is refused).

#include "swlio/daemon/control/control_server.h"

#include <gmock/gmock.h>
#include <grp.h>
#include <gtest/gtest.h>
#include <pwd.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <fstream>
#include <mutex>
#include <thread>

#include "swlio/control/client.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using Clock = std::chrono::steady_clock;

/// Status answers at once; save-map waits until the test finishes it from another thread (the
/// owner thread's role); reset is refused.
class FakeTarget : public ControlTarget {
 public:
  std::string Status() override { return "state: fake\n"; }
  std::shared_ptr<PendingCommand> Submit(const control::Request& r,
                                         control::Reply* refusal) override {
    if (r.command == control::Command::kReset) {
      *refusal = {control::ReplyStatus::kRefused, "no estimator here", ""};
      return nullptr;
    }
    std::lock_guard<std::mutex> lock(mutex);
    pending = std::make_shared<PendingCommand>(r);
    return pending;
  }
  std::shared_ptr<PendingCommand> Pending() {
    std::lock_guard<std::mutex> lock(mutex);
    return pending;
  }
  std::mutex mutex;
  std::shared_ptr<PendingCommand> pending;
};

class ControlServerTest : public ::testing::Test {
 protected:
  void Start(ControlConfig config = {}) {
    dir_ = test::MakeTempDir("control");
    config.socket = (dir_ / "swliod.sock").string();
    config.group = "";
    if (config.request_timeout_s == ControlConfig{}.request_timeout_s)
      config.request_timeout_s = 0.5;
    std::string error, warning;
    server_ = ControlServer::Listen(config, &target_, &error, &warning);
    ASSERT_NE(server_, nullptr) << error;
    EXPECT_EQ(warning, "");
    thread_ = std::thread([this] { server_->Run(stop_, Watchdog::Handle{}); });
  }
  void TearDown() override {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  const std::string& path() const { return server_->path(); }
  control::CallResult Call(control::Command c, std::string arg = "", int timeout_ms = 3000) {
    return control::Call(path(), {c, std::move(arg)}, timeout_ms);
  }
  /// A raw connection (not swlioctl's client), for misbehaving clients.
  int Connect() {
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, path().c_str(), sizeof addr.sun_path - 1);
    const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    EXPECT_EQ(connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0)
        << std::strerror(errno);
    return fd;
  }
  /// Everything the daemon sends until it closes (or 5 s).
  static std::string ReadAll(int fd) {
    timeval tv{5, 0};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    std::string out;
    char buf[512];
    ssize_t n;
    while ((n = recv(fd, buf, sizeof buf, 0)) > 0) out.append(buf, static_cast<size_t>(n));
    close(fd);
    return out;
  }

  std::filesystem::path dir_;
  FakeTarget target_;
  std::unique_ptr<ControlServer> server_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

TEST_F(ControlServerTest, AnswersStatus) {
  Start();
  const control::CallResult r = Call(control::Command::kStatus);
  ASSERT_EQ(r.error, control::CallError::kNone) << r.detail;
  EXPECT_EQ(r.reply.status, control::ReplyStatus::kOk);
  EXPECT_EQ(r.reply.body, "state: fake\n");
  EXPECT_EQ(server_->counters().commands, 1u);
}

TEST_F(ControlServerTest, GarbageGetsAnErrorAndTheServerGoesOn) {
  Start();
  auto send_raw = [this](const std::string& bytes) {
    const int fd = Connect();
    EXPECT_EQ(send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL),
              static_cast<ssize_t>(bytes.size()));
    return ReadAll(fd);
  };
  EXPECT_EQ(send_raw("hello\n"),
            "error bad-request: unknown command 'hello' (commands: status, "
            "save-map PATH, reset)\n");
  EXPECT_THAT(send_raw(std::string("st\0atus\n", 8)),
              StartsWith("error bad-request: control byte"));
  EXPECT_THAT(send_raw("save-map relative.map\n"), HasSubstr("absolute path"));
  EXPECT_THAT(send_raw("status\nstatus\n"), HasSubstr("one request per connection"));
  // 64 KiB without a newline: refused after 4 KiB, the rest never read.
  const int fd = Connect();
  const std::string big(64 * 1024, 'a');
  send(fd, big.data(), big.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  EXPECT_THAT(ReadAll(fd), StartsWith("error bad-request: request longer than 4096 bytes"));
  // A client that closes mid-line gets nothing and costs nothing.
  const int half = Connect();
  send(half, "sta", 3, MSG_NOSIGNAL);
  close(half);
  const control::CallResult r = Call(control::Command::kStatus);
  ASSERT_EQ(r.error, control::CallError::kNone) << r.detail;
  EXPECT_EQ(r.reply.status, control::ReplyStatus::kOk);
  EXPECT_GE(server_->counters().bad_requests, 6u);
}

TEST_F(ControlServerTest, ASilentClientIsDroppedAndBlocksNobody) {
  ControlConfig config;
  config.request_timeout_s = 1.0;
  Start(config);
  const auto t0 = Clock::now();
  const int silent = Connect();
  // Another client is served at once, while the silent one holds its connection.
  const control::CallResult r = Call(control::Command::kStatus);
  ASSERT_EQ(r.error, control::CallError::kNone) << r.detail;
  EXPECT_LT(Clock::now() - t0, std::chrono::milliseconds(800));
  EXPECT_EQ(ReadAll(silent), "error bad-request: no complete request line in time\n");
  EXPECT_GE(Clock::now() - t0, std::chrono::milliseconds(1000));
}

TEST_F(ControlServerTest, TwoClientsAtOnceWhileACommandWaitsForItsThread) {
  Start();
  control::CallResult saved;
  std::thread first([&] { saved = Call(control::Command::kSaveMap, "/maps/a.map", 5000); });
  while (!target_.Pending()) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  // While save-map waits for its owner, a second client is answered.
  const control::CallResult status = Call(control::Command::kStatus, "", 1000);
  ASSERT_EQ(status.error, control::CallError::kNone) << status.detail;
  EXPECT_EQ(status.reply.body, "state: fake\n");
  const control::CallResult reset = Call(control::Command::kReset, "", 1000);
  ASSERT_EQ(reset.error, control::CallError::kNone) << reset.detail;
  EXPECT_EQ(reset.reply.status, control::ReplyStatus::kRefused);
  EXPECT_EQ(reset.reply.message, "no estimator here");
  // The owner finishes it: the first client gets that answer.
  EXPECT_EQ(target_.Pending()->request().argument, "/maps/a.map");
  target_.Pending()->Finish({control::ReplyStatus::kOk, "saved 3 nodes", "nodes: 3\n"});
  first.join();
  ASSERT_EQ(saved.error, control::CallError::kNone) << saved.detail;
  EXPECT_EQ(saved.reply.message, "saved 3 nodes");
  EXPECT_EQ(saved.reply.body, "nodes: 3\n");
}

TEST_F(ControlServerTest, ACommandThatDoesNotFinishTimesOutAndIsCancelled) {
  ControlConfig config;
  config.command_timeout_s = 0.3;
  Start(config);
  const control::CallResult r = Call(control::Command::kSaveMap, "/maps/a.map");
  ASSERT_EQ(r.error, control::CallError::kNone) << r.detail;
  EXPECT_EQ(r.reply.status, control::ReplyStatus::kTimeout);
  EXPECT_THAT(r.reply.message, HasSubstr("may still complete"));
  EXPECT_TRUE(target_.Pending()->cancelled()) << "the owner will not start it";
  EXPECT_EQ(server_->counters().timeouts, 1u);
}

TEST_F(ControlServerTest, OneClientOverMaxClientsIsTurnedAway) {
  ControlConfig config;
  config.max_clients = 1;
  config.request_timeout_s = 2.0;
  Start(config);
  const int silent = Connect();
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // accepted first
  const control::CallResult r = Call(control::Command::kStatus);
  ASSERT_EQ(r.error, control::CallError::kNone) << r.detail;
  EXPECT_EQ(r.reply.status, control::ReplyStatus::kBusy);
  close(silent);
}

TEST_F(ControlServerTest, SocketIs0660AndRemovedAtTheEnd) {
  Start();
  struct stat st {};
  ASSERT_EQ(stat(path().c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  EXPECT_EQ(st.st_mode & 07777, 0660u);
  EXPECT_EQ(st.st_uid, geteuid());
  stop_ = true;
  thread_.join();
  const std::string p = path();
  server_.reset();
  EXPECT_NE(stat(p.c_str(), &st), 0);
  EXPECT_EQ(control::Call(p, {}, 500).error, control::CallError::kNoDaemon);
}

TEST(ControlServerListen, ReplacesAStaleSocketButNotALiveOne) {
  const auto dir = test::MakeTempDir("control-stale");
  ControlConfig config;
  config.socket = (dir / "s.sock").string();
  config.group = "";
  FakeTarget target;
  std::string error, warning;
  {
    // A socket file nobody listens on (a daemon that was killed).
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    std::strncpy(addr.sun_path, config.socket.c_str(), sizeof addr.sun_path - 1);
    const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    ASSERT_EQ(bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
    close(fd);
  }
  auto first = ControlServer::Listen(config, &target, &error, &warning);
  ASSERT_NE(first, nullptr) << error;
  auto second = ControlServer::Listen(config, &target, &error, &warning);
  EXPECT_EQ(second, nullptr);
  EXPECT_THAT(error, HasSubstr("another process"));
  // A directory that does not exist (swliod run by hand, no /run/swlio): an error to log.
  config.socket = (dir / "missing" / "s.sock").string();
  EXPECT_EQ(ControlServer::Listen(config, &target, &error, &warning), nullptr);
  EXPECT_THAT(error, HasSubstr("No such file or directory"));
  // A regular file at the path is never removed.
  config.socket = (dir / "file").string();
  { std::ofstream(config.socket) << "x"; }
  EXPECT_EQ(ControlServer::Listen(config, &target, &error, &warning), nullptr);
  EXPECT_THAT(error, HasSubstr("not a socket"));
  EXPECT_TRUE(std::filesystem::exists(config.socket));
}

TEST(ControlServerListen, AppliesTheGroupOrSaysWhyNot) {
  const auto dir = test::MakeTempDir("control-group");
  FakeTarget target;
  ControlConfig config;
  config.socket = (dir / "s.sock").string();
  // One of this process's groups other than its primary when there is one (chown works).
  std::vector<gid_t> groups(static_cast<size_t>(getgroups(0, nullptr)));
  getgroups(static_cast<int>(groups.size()), groups.data());
  gid_t gid = getegid();
  for (gid_t g : groups) gid = g != getegid() ? g : gid;
  const group* gr = getgrgid(gid);
  ASSERT_NE(gr, nullptr);
  config.group = gr->gr_name;
  std::string error, warning;
  auto server = ControlServer::Listen(config, &target, &error, &warning);
  ASSERT_NE(server, nullptr) << error;
  EXPECT_EQ(warning, "");
  struct stat st {};
  ASSERT_EQ(stat(config.socket.c_str(), &st), 0);
  EXPECT_EQ(st.st_gid, gid);
  server.reset();
  config.group = "swlio-no-such-group";
  server = ControlServer::Listen(config, &target, &error, &warning);
  ASSERT_NE(server, nullptr) << error;
  EXPECT_THAT(warning, HasSubstr("'swlio-no-such-group' does not exist"));
}

TEST(ControlPeer, AllowedAreRootTheDaemonsUserAndItsGroups) {
  ControlAccess access{1000, 1000, gid_t{2000}};
  auto peer = [](uid_t uid, gid_t gid, std::vector<gid_t> groups) {
    PeerCredentials p;
    p.uid = uid;
    p.gid = gid;
    p.groups = std::move(groups);
    p.groups_known = true;
    return p;
  };
  EXPECT_TRUE(PeerAllowed(peer(0, 0, {}), access));
  EXPECT_TRUE(PeerAllowed(peer(1000, 1000, {}), access));
  EXPECT_TRUE(PeerAllowed(peer(1001, 2000, {}), access));          // primary: operators
  EXPECT_TRUE(PeerAllowed(peer(1001, 1001, {27, 2000}), access));  // supplementary
  EXPECT_TRUE(PeerAllowed(peer(1001, 1000, {}), access));          // the daemon's group
  EXPECT_FALSE(PeerAllowed(peer(1001, 1001, {27, 100}), access));
  EXPECT_FALSE(PeerAllowed(peer(65534, 65534, {}), access));
  access.operator_gid.reset();  // control.group empty or unknown
  EXPECT_FALSE(PeerAllowed(peer(1001, 2000, {}), access));
}

TEST(ControlPeer, CredentialsOfAConnectedPeer) {
  int sv[2];
  ASSERT_EQ(socketpair(AF_UNIX, SOCK_STREAM, 0, sv), 0);
  const std::optional<PeerCredentials> p = ReadPeerCredentials(sv[0]);
  close(sv[0]);
  close(sv[1]);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->pid, getpid());
  EXPECT_EQ(p->uid, geteuid());
  EXPECT_EQ(p->gid, getegid());
  EXPECT_THAT(DescribePeer(*p), HasSubstr(std::string("uid ").append(std::to_string(geteuid()))));
}

// What a child that dropped to `nobody` (uid and every group) got from the socket.
enum NobodyGot { kEacces = 1, kOtherConnectError = 2, kRefusedReply = 3, kOkReply = 4, kOther = 5 };

/// The child uses system calls only (no allocation after fork in a threaded test program).
int AsNobody(const std::string& socket_path) {
  const passwd* nobody = getpwnam("nobody");
  if (nobody == nullptr) return -1;
  const uid_t uid = nobody->pw_uid;
  const gid_t gid = nobody->pw_gid;
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strncpy(addr.sun_path, socket_path.c_str(), sizeof addr.sun_path - 1);
  const pid_t pid = fork();
  if (pid == 0) {
    if (setgroups(0, nullptr) != 0 || setgid(gid) != 0 || setuid(uid) != 0) _exit(100);
    const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    if (connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
      _exit(errno == EACCES ? kEacces : kOtherConnectError);
    const char request[] = "status\n";
    if (send(fd, request, sizeof request - 1, MSG_NOSIGNAL) < 0) _exit(kOther);
    char reply[64] = {};
    size_t got = 0;
    ssize_t n;
    while (got < sizeof reply - 1 && (n = recv(fd, reply + got, sizeof reply - 1 - got, 0)) > 0)
      got += static_cast<size_t>(n);
    if (std::strncmp(reply, "error refused:", 14) == 0) _exit(kRefusedReply);
    _exit(std::strncmp(reply, "ok", 2) == 0 ? kOkReply : kOther);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -2;
}

TEST_F(ControlServerTest, OthersAreRefusedByTheFileAndByTheCredentialsCheck) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to drop to nobody in a child";
  if (getpwnam("nobody") == nullptr) GTEST_SKIP() << "no user nobody";
  Start();
  // The directory may be traversed by all: only the socket's own mode keeps nobody out.
  ASSERT_EQ(chmod(dir_.c_str(), 0755), 0);
  EXPECT_EQ(AsNobody(path()), kEacces);
  EXPECT_EQ(server_->counters().connections, 0u) << "refused by the kernel: never accepted";
  // The socket's mode widened by hand: the daemon's own check still refuses, and says so.
  ASSERT_EQ(chmod(path().c_str(), 0666), 0);
  EXPECT_EQ(AsNobody(path()), kRefusedReply);
  EXPECT_EQ(server_->counters().refused_peers, 1u);
  // Root itself is served.
  EXPECT_EQ(Call(control::Command::kStatus).reply.status, control::ReplyStatus::kOk);
}

}  // namespace
}  // namespace swlio::daemon
