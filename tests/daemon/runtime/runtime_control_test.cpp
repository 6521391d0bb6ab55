// swlioctl's commands against a Runtime (control_server.h, runtime_control.cpp): on a live
// simulated drive with loop closure, `status` says the state and the published health,
// `save-map` writes a map that loads back while mapping, a second client is answered while
// the save runs, and `reset` re-initializes the estimator, which tracks again; without a drive,
// save-map is refused when loop closure is off or when localizing in a saved map.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <thread>

#include "box_yard_map.h"
#include "live_drive.h"
#include "swlio/control/client.h"
#include "swlio/estimator/map/saved_map.h"

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

control::CallResult Ask(const std::string& socket,
                        control::Command command,
                        std::string argument = "",
                        int timeout_ms = 5000) {
  return control::Call(socket, {command, std::move(argument)}, timeout_ms);
}

/// The value of "  key: value" under the published status `name` in a status body (-1: none).
long StatusValue(const std::string& body, const std::string& name, const std::string& key) {
  const size_t at = body.find(" " + name + ": ");
  if (at == std::string::npos) return -1;
  const size_t k = body.find("\n  " + key + ": ", at);
  if (k == std::string::npos) return -1;
  return std::atol(body.c_str() + k + key.size() + 5);
}

/// Polls `status` until `pred` holds for its body, up to `timeout`; the last body.
std::string StatusWhen(const std::string& socket,
                       const std::function<bool(const std::string&)>& pred,
                       std::chrono::seconds timeout) {
  const auto deadline = Clock::now() + timeout;
  std::string body;
  while (Clock::now() < deadline) {
    const control::CallResult r = Ask(socket, control::Command::kStatus);
    if (r.error == control::CallError::kNone) {
      body = r.reply.body;
      if (pred(body)) return body;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  return body;
}

/// The value of an unindented line "key: value" of a status body (-1: none); the published
/// statuses' values are indented.
long TopValue(const std::string& body, const std::string& key) {
  const std::string line = key + ": ";
  if (body.compare(0, line.size(), line) == 0) return std::atol(body.c_str() + line.size());
  const size_t k = body.find("\n" + line);
  return k == std::string::npos ? -1 : std::atol(body.c_str() + k + 1 + line.size());
}

bool Has(const std::string& body, const std::string& text) {
  return body.find(text) != std::string::npos;
}

struct ClientOutcome {
  std::string tracking_status;  ///< the first status body that said tracking with 3+ nodes
  control::CallResult save;
  control::CallResult status_during_save;
  std::string map_path;
  control::CallResult reset;
  std::string after_reset;  ///< status right after the reset
  std::string tracking_again;
  /// When each step ended, in simulation seconds (the drive is 16 s): the failure messages'.
  std::string timeline;
};

TEST(RuntimeControl, StatusSaveMapAndResetOnALiveDrive) {
  const auto dir = ::swlio::test::MakeTempDir("runtime-control");
  const std::string socket = (dir / "swliod.sock").string();
  test::LiveDrive drive;
  drive.duration_s = 16.0;
  drive.dds_domain = 159;
  drive.adjust_config = [&](DaemonConfig* c) {
    c->loop_closure.enabled = true;
    c->control.socket = socket;
    c->control.group = "";
  };
  ClientOutcome out;
  out.map_path = (dir / "live.map").string();
  // The 40 s run from the simulator's start: a sanitized build first casts the whole drive,
  // which on a loaded machine took longer than that (an ASan run asked 40 s into the precast).
  std::atomic<bool> streaming{false};
  std::atomic<int64_t> sim_start_ns{0};
  std::atomic<double> sim_speed{1.0};
  drive.on_sim_start = [&](int64_t start_ns, double speed) {
    sim_start_ns = start_ns;
    sim_speed = speed;
    streaming = true;
  };
  auto step = [&](const char* what) {
    const double t = static_cast<double>(MonotonicNowNs() - sim_start_ns) * 1e-9 * sim_speed;
    out.timeline += std::string(what) + " at " + std::to_string(t) + " s; ";
  };
  std::thread client([&] {
    for (int i = 0; i < 3000 && !streaming; ++i)  // ≤ 300 s
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    out.tracking_status = StatusWhen(
        socket,
        [](const std::string& b) {
          return Has(b, "state: tracking") && StatusValue(b, "swlio: loop closure", "nodes") >= 3;
        },
        std::chrono::seconds(40));
    step("tracking");
    // Two clients at once: save-map, and status while it runs.
    std::thread second([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      out.status_during_save = Ask(socket, control::Command::kStatus);
    });
    out.save = Ask(socket, control::Command::kSaveMap, out.map_path, 30000);
    second.join();
    step("saved");
    out.reset = Ask(socket, control::Command::kReset);
    out.after_reset = Ask(socket, control::Command::kStatus).reply.body;
    step("reset");
    out.tracking_again = StatusWhen(
        socket, [](const std::string& b) { return Has(b, "state: tracking"); },
        std::chrono::seconds(20));
    step("tracking again");
  });
  const test::LiveDriveResult r = test::RunLiveDrive(drive);
  client.join();
  ASSERT_TRUE(r.sim_ok) << r.error;
  std::cout << "[ client ] " << out.timeline << "\n";

  // status: the state, the mode, and the health topic's statuses with their values.
  std::cout << "[ status ]\n" << out.tracking_status;
  EXPECT_THAT(out.tracking_status, HasSubstr("state: tracking\nmode: mapping\nready: true\n"))
      << out.timeline;
  EXPECT_THAT(out.tracking_status, HasSubstr("ok swlio: lidar: streaming\n  packets_hz: "));
  EXPECT_THAT(out.tracking_status, HasSubstr(" swlio: estimator: "));
  EXPECT_THAT(out.tracking_status, HasSubstr(" swlio: loop closure: "));
  // 400 Hz of sensor time; rates are per host second, so a reader starved for a quarter of
  // that second counts 300 (299 seen in Release beside a test that simulates and replays a
  // drive, the simulator < 200 ms late). Release only, and only when the simulator was on
  // time: under TSan at 0.5x beside other tests the daemon's own reader fell behind within the
  // 1 s window (104 Hz counted with the simulator on time).
  if (!test::kSanitized && r.stats.max_lateness_ms < 200.0) {
    EXPECT_GT(static_cast<double>(StatusValue(out.tracking_status, "swlio: imu", "rate_hz")),
              200.0 * r.speed);
  }

  // save-map while mapping: the file loads back with the map loader, as many nodes as said.
  ASSERT_EQ(out.save.error, control::CallError::kNone) << out.save.detail << "; " << out.timeline;
  ASSERT_EQ(out.save.reply.status, control::ReplyStatus::kOk) << out.save.reply.message;
  std::cout << "[ save-map ] " << out.save.reply.message << "\n" << out.save.reply.body;
  std::string error;
  const std::optional<estimator::SavedMap> map = estimator::LoadMapFile(out.map_path, &error);
  ASSERT_TRUE(map.has_value()) << error;
  // Every node the daemon had when the client saw it tracking is in the file: 3 when the
  // estimator kept up; a starved sanitizer build may end its drive with fewer (1 seen under TSan).
  const long nodes_seen = StatusValue(out.tracking_status, "swlio: loop closure", "nodes");
  EXPECT_GE(static_cast<long>(map->nodes.size()), std::max(1L, nodes_seen));
  if (r.stats.max_lateness_ms < 200.0 && r.speed >= 1.0) {
    EXPECT_GE(map->nodes.size(), 3u);
  }
  EXPECT_THAT(out.save.reply.body,
              HasSubstr(std::string("nodes: ").append(std::to_string(map->nodes.size()))));
  EXPECT_GT(std::filesystem::file_size(out.map_path + ".pcd"), 1000u);
  // The second client, at the same time, got its status.
  ASSERT_EQ(out.status_during_save.error, control::CallError::kNone)
      << out.status_during_save.detail;
  EXPECT_THAT(out.status_during_save.reply.body, HasSubstr("mode: mapping"));

  // reset: answered ok, the estimator starts again, and tracks again later in the drive.
  ASSERT_EQ(out.reset.error, control::CallError::kNone) << out.reset.detail;
  EXPECT_EQ(out.reset.reply.status, control::ReplyStatus::kOk) << out.reset.reply.message;
  // Right after the reply, the reset is counted. The state may already be tracking again: a
  // sweep queued behind the reset re-initializes at once (seen 0.2 ms after the reply).
  EXPECT_EQ(TopValue(out.after_reset, "reinitializations"),
            TopValue(out.tracking_status, "reinitializations") + 1)
      << out.after_reset;
  EXPECT_EQ(TopValue(out.after_reset, "operator_resets"), 1) << out.after_reset;
  EXPECT_THAT(out.tracking_again, HasSubstr("state: tracking")) << out.timeline;
  EXPECT_GE(r.final.optimizer.reinitializations, 1u);
  EXPECT_EQ(r.final.optimizer.operator_resets, 1u);
}

/// A Runtime without a drive and without DDS: enough to ask it.
std::unique_ptr<Runtime> IdleRuntime(DaemonConfig config, std::string* error) {
  config.lidar.bind_address = "127.0.0.1";
  config.lidar.msop_port = ::swlio::test::QuietUdpPort();
  config.lidar.difop_port = ::swlio::test::QuietUdpPort();
  config.imu.device = "/nonexistent/imu";
  RuntimeOptions options;
  options.dds = false;
  return Runtime::Create(config, options, error);
}

TEST(RuntimeControlIdle, SaveMapIsRefusedWithoutLoopClosureOrWhileLocalizing) {
  const auto dir = ::swlio::test::MakeTempDir("runtime-control-idle");
  DaemonConfig config;
  config.loop_closure.enabled = false;  // on by default
  config.control.socket = (dir / "a.sock").string();
  config.control.group = "";
  std::string error;
  auto rt = IdleRuntime(config, &error);
  ASSERT_NE(rt, nullptr) << error;
  EXPECT_EQ(rt->control_socket(), config.control.socket);
  rt->Start();
  control::CallResult save = Ask(config.control.socket, control::Command::kSaveMap, "/tmp/x.map");
  ASSERT_EQ(save.error, control::CallError::kNone) << save.detail;
  EXPECT_EQ(save.reply.status, control::ReplyStatus::kRefused);
  EXPECT_THAT(save.reply.message, HasSubstr("loop closure is off"));
  const control::CallResult status = Ask(config.control.socket, control::Command::kStatus);
  EXPECT_THAT(status.reply.body, HasSubstr("state: initializing\nmode: odometry\nready: false\n"));
  rt->Stop();
  EXPECT_EQ(rt->control_socket(), "");
  EXPECT_FALSE(std::filesystem::exists(config.control.socket)) << "removed at stop";

  // Localizing in a saved map.
  const auto map_path = dir / "yard.map";
  ASSERT_TRUE(estimator::SaveMapFile(map_path.string(),
                                     ::swlio::test::BoxYardMap(::swlio::test::BoxYard(7)), &error))
      << error;
  config.map.localize = true;
  config.map.load_path = map_path.string();
  config.loop_closure.enabled = true;  // off while localizing
  config.control.socket = (dir / "b.sock").string();
  rt = IdleRuntime(config, &error);
  ASSERT_NE(rt, nullptr) << error;
  rt->Start();
  save = Ask(config.control.socket, control::Command::kSaveMap, "/tmp/x.map");
  ASSERT_EQ(save.error, control::CallError::kNone) << save.detail;
  EXPECT_EQ(save.reply.status, control::ReplyStatus::kRefused);
  EXPECT_THAT(save.reply.message, HasSubstr("localizing in the fixed map " + map_path.string()));
  EXPECT_FALSE(std::filesystem::exists("/tmp/x.map"));
}

TEST(RuntimeControlIdle, AnUnusableSocketPathLeavesTheDaemonRunningWithoutControl) {
  DaemonConfig config;
  config.control.socket = "/nonexistent-swlio-dir/swliod.sock";
  std::string error;
  auto rt = IdleRuntime(config, &error);
  ASSERT_NE(rt, nullptr) << error;
  EXPECT_EQ(rt->control_socket(), "");
  rt->Start();
  rt->Stop();
  config.control.socket = "";  // off
  rt = IdleRuntime(config, &error);
  ASSERT_NE(rt, nullptr) << error;
  EXPECT_EQ(rt->control_socket(), "");
}

}  // namespace
}  // namespace swlio::daemon
