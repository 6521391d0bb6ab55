// Operators' pose hints on a live daemon (issue 34): rviz2's /initialpose over DDS and
// `swlioctl relocalize` over the control socket. DDS domain 162.
//
// First a live `short` drive builds a map (loop closure, saved at stop). Then the same drive
// again, localizing in that map with global relocalization switched off
// (relocalize_max_descriptor_distance 0: no place descriptor is near enough), so that only a
// hint can localize it: while the robot stands at the start, a hint 30 m off is refused with a
// reason, the right one localizes within 2 s (the first map-frame pose arrives), and a wrong
// swlioctl relocalize is refused without moving the pose. The right hint comes from Fast DDS
// (swlio-fastdds-echo --initialpose, as rviz2 on the default ROS 2 middleware sends it), which
// as a tf2 listener then sees the daemon relocalize: the TF chain map → odom → base_link at
// each pose's stamp is the published pose. Without Fast DDS a Cyclone DDS writer sends it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>

#include "line_collector.h"
#include "live_drive.h"
#include "swlio/control/client.h"
#include "swlio/ipc/publisher.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;
using Clock = std::chrono::steady_clock;

constexpr uint32_t kDomain = 162;
constexpr double kStandS = 9.0;  // standing at the start: the hints arrive while it stands

struct BasePose {
  double x = 0.0, y = 0.0, yaw = 0.0;
};

BasePose PoseOf(const ipc::PoseWithCovarianceStamped& m) {
  const auto& q = m.pose.orientation_xyzw;
  const Eigen::Matrix3d R = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).toRotationMatrix();
  return {m.pose.position_m[0], m.pose.position_m[1], std::atan2(R(1, 0), R(0, 0))};
}

/// rviz2's "2D Pose Estimate" as it sends it: base_link in map, x/y variance 0.25, yaw 0.0685.
ipc::PoseWithCovarianceStamped InitialPose(const BasePose& p) {
  ipc::PoseWithCovarianceStamped m;
  m.frame_id = "map";
  m.pose.position_m = {p.x, p.y, 0.0};
  m.pose.orientation_xyzw = {0.0, 0.0, std::sin(p.yaw / 2.0), std::cos(p.yaw / 2.0)};
  m.covariance[0] = 0.25;
  m.covariance[7] = 0.25;
  m.covariance[35] = 0.06853891945200942;
  return m;
}

/// Waits until simulation time `t_s` of a drive that started at `start_ns` (host time).
void SleepUntilSim(const std::atomic<int64_t>& start_ns, double speed, double t_s) {
  while (start_ns.load() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const int64_t at = start_ns.load() + static_cast<int64_t>(t_s / speed * 1e9);
  while (MonotonicNowNs() < at) std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

TEST(RuntimeInitialPose, AHintLocalizesWithinTwoSecondsAndAWrongOneIsRefused) {
  const auto dir = ::swlio::test::MakeTempDir("runtime-initialpose");
  const std::string map_path = (dir / "short.map").string();

  // The map: the first 15 s of the drive (6 m driven), saved at stop.
  test::LiveDrive mapping;
  mapping.duration_s = 15.0;
  mapping.stand_start_s = kStandS;
  mapping.dds_domain = kDomain;
  mapping.adjust_config = [&](DaemonConfig* c) {
    c->loop_closure.enabled = true;
    c->map.save_path = map_path;
  };
  const test::LiveDriveResult m = test::RunLiveDrive(mapping);
  ASSERT_TRUE(m.sim_ok) << m.error;
  ASSERT_TRUE(std::filesystem::exists(map_path));
  ASSERT_FALSE(m.poses.empty());
  // Where the robot stands, in the map's frame: its first published pose.
  const BasePose start = PoseOf(m.poses.front().msg);
  std::printf("[ hint ] start in the map: (%.3f, %.3f) yaw %.2f deg\n", start.x, start.y,
              start.yaw * 180.0 / M_PI);

  // Localizing: hints from a DDS publisher (the operator's rviz2) and from swlioctl.
  const std::string socket = (dir / "swliod.sock").string();
  test::LiveDrive drive;
  drive.duration_s = 14.0;
  drive.stand_start_s = kStandS;
  drive.dds_domain = kDomain;
  drive.adjust_config = [&](DaemonConfig* c) {
    c->map.localize = true;
    c->map.load_path = map_path;
    c->localization.relocalize_max_descriptor_distance = 0.0;
    c->ipc.initialpose_topic = "initialpose";
    c->control.socket = socket;
    c->control.group = "";
  };
  std::atomic<int64_t> start_ns{0};
  drive.on_sim_start = [&](int64_t t0, double) { start_ns = t0; };
  const double speed = test::kSanitized ? 0.5 : 1.0;
  std::atomic<int64_t> right_hint_ns{0};
  const BasePose right{start.x + 0.4, start.y - 0.3, start.yaw + 0.1};
  const auto kept = dir / "fastdds.txt";
  std::unique_ptr<test::ChildProcess> fastdds;
  std::unique_ptr<test::LineCollector> fastdds_lines;
#ifdef SWLIO_HAVE_FASTDDS_ECHO
  // Started with the drive; it sends the right hint 5 s later (sim time ≈ 5.5 s at 1×).
  drive.on_sim_start = [&](int64_t t0, double s) {
    start_ns = t0;
    char hint[128];
    std::snprintf(hint, sizeof hint, "%.6f,%.6f,%.6f@%.3f", right.x, right.y,
                  right.yaw * 180.0 / M_PI, 5.5 / s);
    fastdds = std::make_unique<test::ChildProcess>(std::vector<std::string>{
        ::swlio::test::ToolPath("swlio-fastdds-echo").string(), "--profile",
        (::swlio::test::SourceDir() / "config" / "fastdds-loopback.xml").string(), "--domain",
        std::to_string(kDomain), "--tf-check", "--timeout", std::to_string(16.0 / s),
        "--initialpose", hint});
    fastdds_lines = std::make_unique<test::LineCollector>(fastdds.get(), kept);
  };
  const bool fastdds_sends = true;
#else
  const bool fastdds_sends = false;
#endif
  control::CallResult wrong_ctl;
  std::string error;
  std::thread operator_thread([&] {
    ipc::IpcConfig config = test::LiveDriveConfig(dir, kDomain).ipc;
    config.pose_topic = "initialpose";
    auto participant = ipc::Participant::Create(config, &error);
    if (!participant) return;
    ipc::PublisherOptions only_pose;
    only_pose.topics.fill(false);
    only_pose.topics[static_cast<size_t>(ipc::Topic::kPose)] = true;
    auto writer = ipc::Publisher::Create(*participant, config, only_pose, &error);
    if (!writer) return;
    SleepUntilSim(start_ns, speed, 4.5);  // initialized and standing
    writer->PublishPose(InitialPose({start.x - 30.0, start.y, start.yaw}));
    SleepUntilSim(start_ns, speed, 5.5);
    if (!fastdds_sends) {
      right_hint_ns = MonotonicNowNs();
      writer->PublishPose(InitialPose(right));
    }
    SleepUntilSim(start_ns, speed, 7.5);
    // 20 m off, inside the map's 30 m reach (submap_radius_m), so the scan is what refuses it.
    const std::string wrong = std::to_string(start.x) + " " + std::to_string(start.y + 20.0) + " " +
                              std::to_string(start.yaw * 180.0 / M_PI + 90.0);
    wrong_ctl = control::Call(socket, {control::Command::kRelocalize, wrong}, 20000);
  });
  const test::LiveDriveResult r = test::RunLiveDrive(drive);
  operator_thread.join();
  std::vector<test::Line> lines;
  if (fastdds_lines) {
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    lines = fastdds_lines->Stop();
  }
  size_t tf_matched = 0;
  double tf_max_err_m = 0.0;
  for (const test::Line& l : lines) {
    if (l.kind == "initialpose") {
      EXPECT_EQ(l.Int("written"), 1);
      right_hint_ns = l.Int("sent_mono_ns");
    }
    if (l.kind == "tf_check" && l.Int("matched") == 1) {
      ++tf_matched;
      tf_max_err_m = std::max(tf_max_err_m, l.Get("pos_err_m"));
    }
  }
  if (fastdds_sends) {
    std::printf("[ hint ] Fast DDS: %zu poses matched by the TF chain, max error %.2e m\n",
                tf_matched, tf_max_err_m);
    EXPECT_GT(tf_matched, 100u) << "the Fast DDS listener never saw the relocalized pose: "
                                << kept.string();
    EXPECT_LT(tf_max_err_m, 1e-3);
  }
  ASSERT_TRUE(r.sim_ok) << r.error;
  ASSERT_TRUE(error.empty()) << error;
  r.ShowPublished("swlio: localization");

  const LocalizationCounters& loc = r.final.localization;
  EXPECT_EQ(loc.hints, 3u);
  EXPECT_EQ(loc.hints_refused, 2u);
  // The 30 m hint was refused, with the reason in the health message of that moment.
  bool refusal_published = false;
  for (const auto& a : r.published_health) {
    for (const auto& s : a.msg.status) {
      if (s.name == "swlio: localization" && s.message.find("pose hint refused: ") == 0)
        refusal_published = true;
    }
  }
  EXPECT_TRUE(refusal_published);
  // The right hint: the first map-frame pose within 2 s, where the robot stands.
  ASSERT_FALSE(r.poses.empty()) << "never localized";
  ASSERT_GT(right_hint_ns.load(), 0) << "the right hint was not sent";
  const double after_s =
      static_cast<double>(r.poses.front().receive_steady_ns - right_hint_ns.load()) * 1e-9;
  const BasePose first = PoseOf(r.poses.front().msg);
  std::printf("[ hint ] first map pose %.2f s after the hint, at (%.3f, %.3f)\n", after_s, first.x,
              first.y);
  EXPECT_GT(after_s, 0.0);
  EXPECT_LT(after_s, 2.0);
  EXPECT_LT(std::hypot(first.x - start.x, first.y - start.y), 0.1);
  // swlioctl relocalize 20 m off and turned: refused, with the reason; still localized.
  ASSERT_EQ(wrong_ctl.error, control::CallError::kNone) << wrong_ctl.detail;
  EXPECT_EQ(wrong_ctl.reply.status, control::ReplyStatus::kRefused);
  EXPECT_THAT(wrong_ctl.reply.message, HasSubstr("does not fit the map"));
  std::printf("[ hint ] swlioctl: %s\n", wrong_ctl.reply.message.c_str());
  EXPECT_EQ(loc.state, estimator::LocalizationState::kTracking);
  // It drove off after the stand and stayed localized (poses to the end of the drive).
  EXPECT_GT(r.PosesBetween(kStandS + 2.0, 14.0), 300u);
}

}  // namespace
}  // namespace swlio::daemon
