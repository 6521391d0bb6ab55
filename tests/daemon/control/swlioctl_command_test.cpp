// swlioctl (tools/ctl/main.cpp) as a script uses it: its exit codes and what it prints, against
// a control thread (control_server.h) with a fake target, and with no daemon at all.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <thread>

#include "swlio/daemon/control/control_server.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;

/// save-map answers at once with the path it got (or never, for /never); reset is refused.
class ScriptedTarget : public ControlTarget {
 public:
  std::string Status() override { return "state: tracking\nmode: mapping\n"; }
  std::shared_ptr<PendingCommand> Submit(const control::Request& r,
                                         control::Reply* refusal) override {
    if (r.command == control::Command::kReset) {
      *refusal = {control::ReplyStatus::kRefused, "estimator.mode is lidar-only", ""};
      return nullptr;
    }
    auto pending = std::make_shared<PendingCommand>(r);
    if (r.argument != "/never") {
      pending->Finish({control::ReplyStatus::kOk, "saved 5 nodes", "map: " + r.argument + "\n"});
    }
    return pending;
  }
};

class SwlioctlCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::MakeTempDir("swlioctl");
    ControlConfig config;
    config.socket = (dir_ / "s.sock").string();
    config.group = "";
    config.command_timeout_s = 0.5;
    std::string error, warning;
    server_ = ControlServer::Listen(config, &target_, &error, &warning);
    ASSERT_NE(server_, nullptr) << error;
    thread_ = std::thread([this] { server_->Run(stop_, Watchdog::Handle{}); });
  }
  void TearDown() override {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  /// stdout and stderr of `swlioctl --socket S ARGS`, run in dir_; *code its exit status.
  std::string Run(const std::string& args, int* code, const std::string& prefix = "") {
    const std::string swlioctl = ::swlio::test::ToolPath("swlioctl").string();
    std::string command = "cd ";
    command += dir_.string() + " && " + prefix + swlioctl + " --socket " + server_->path() + " " +
               args + " 2>&1";
    return test::RunCommand(command, code);
  }

  std::filesystem::path dir_;
  ScriptedTarget target_;
  std::unique_ptr<ControlServer> server_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

TEST_F(SwlioctlCommand, ExitCodesAndOutputForScripts) {
  int code = -1;
  EXPECT_EQ(Run("status", &code), "state: tracking\nmode: mapping\n");
  EXPECT_EQ(code, 0);
  // A relative path is sent made absolute against swlioctl's own directory.
  std::string saved = "saved 5 nodes\nmap: ";
  saved += (dir_ / "site.map").string() + "\n";
  EXPECT_EQ(Run("save-map site.map", &code), saved);
  EXPECT_EQ(code, 0);
  EXPECT_EQ(Run("reset", &code), "swlioctl: reset: refused: estimator.mode is lidar-only\n");
  EXPECT_EQ(code, 1);
  EXPECT_THAT(Run("save-map /never", &code), HasSubstr("swlioctl: save-map: timeout: "));
  EXPECT_EQ(code, 75);
  EXPECT_THAT(Run("", &code), HasSubstr("A subcommand is required"));
  EXPECT_EQ(code, 64);
  EXPECT_THAT(Run("save-map", &code), HasSubstr("PATH is required"));
  EXPECT_EQ(code, 64);
  EXPECT_EQ(Run("status --bogus", &code).empty(), false);
  EXPECT_EQ(code, 64);
}

TEST_F(SwlioctlCommand, NoDaemonAndNoPermission) {
  int code = -1;
  const std::string swlioctl = ::swlio::test::ToolPath("swlioctl").string();
  EXPECT_THAT(test::RunCommand(
                  swlioctl + " --socket " + (dir_ / "none.sock").string() + " status 2>&1", &code),
              HasSubstr("No such file or directory"));
  EXPECT_EQ(code, 69);
  if (geteuid() != 0 || access("/usr/bin/setpriv", X_OK) != 0) {
    GTEST_SKIP() << "permission check needs root and setpriv to run swlioctl as nobody";
  }
  ASSERT_EQ(chmod(dir_.c_str(), 0755), 0);  // only the socket's own mode (0660) stands in the way
  const std::string out =
      Run("status", &code, "setpriv --reuid=nobody --regid=nogroup --clear-groups ");
  EXPECT_THAT(out, HasSubstr("Permission denied"));
  EXPECT_EQ(code, 77);
}

}  // namespace
}  // namespace swlio::daemon
