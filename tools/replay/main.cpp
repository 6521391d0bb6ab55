// swlio-replay: feeds a recording folder (swliod --record, or the simulator's) or a ROS bag
// (bag_input.h) through the same
// decoders, clock models and estimator as the live daemon, writes the trajectory (TUM, IMU
// frame, sweep ends) and, with --dds-config, publishes the odometry and keyframe path on the
// daemon's topics.
//
// Events are processed in recorded order and none is dropped. By default they are paced at
// the recorded speed (× --speed), so subscribers see them as they came; --deterministic
// processes as fast as possible and guarantees byte-identical output on every run (no clock
// is read: stage timings are not taken). A daemon recording or black-box incident is replayed
// with the configuration it carries (config.yaml) unless --config says otherwise, and a
// recording made by another version is named as such.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <thread>

#include "../common/bag_options.h"
#include "swlio/daemon/config/config_loader.h"
#include "swlio/daemon/output/message_conversion.h"
#include "swlio/daemon/output/tum_output.h"
#include "swlio/daemon/pipeline/estimator_runner.h"
#include "swlio/daemon/recording/input_open.h"
#include "swlio/daemon/recording/recording_provenance.h"
#include "swlio/daemon/runtime/version.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/publisher.h"

namespace {

struct Options {
  std::string dir, out, config, dds_config;
  int64_t domain = 0;
  double speed = 1.0;
  bool deterministic = false;
  swlio::tools::BagCliOptions bag;
};

/// Publishes what the daemon's publisher thread would for each sweep.
class DdsOut {
 public:
  bool Open(const Options& opt, std::string* error) {
    swlio::ipc::IpcConfig ipc;
    ipc.dds_config_file = opt.dds_config;
    ipc.domain_id = opt.domain;
    participant_ = swlio::ipc::Participant::Create(ipc, error);
    if (!participant_) return false;
    publisher_ = swlio::ipc::Publisher::Create(*participant_, ipc, error);
    path_.frame_id = frames_.map;
    return publisher_ != nullptr;
  }
  /// `state`: the sweep's state with its stamp on the host clock.
  void Sweep(const swlio::State& state, const swlio::estimator::WindowResult& r) {
    // The IMU's odometry (no base frame, no TF: a replay publishes the estimate only).
    const swlio::ipc::Odometry m =
        swlio::daemon::ToOdometryMessage(state, Eigen::Vector3d::Zero(), r.covariance,
                                         Eigen::Isometry3d::Identity(), frames_.map, frames_.imu);
    publisher_->PublishOdometry(m);
    if (!r.odometry.keyframe) return;
    path_.poses.push_back({m.t_ns, frames_.map, m.pose});
    path_.t_ns = m.t_ns;
    publisher_->PublishPath(path_);
  }

 private:
  swlio::ipc::FrameNames frames_;
  std::unique_ptr<swlio::ipc::Participant> participant_;
  std::unique_ptr<swlio::ipc::Publisher> publisher_;
  swlio::ipc::Path path_;
};

int Run(Options opt) {
  // A daemon recording or incident carries its configuration: replay what the daemon ran.
  if (opt.config.empty()) {
    if (auto recorded = swlio::daemon::RecordedConfigFile(opt.dir)) {
      opt.config = recorded->string();
      std::cerr << "swlio-replay: the recording's configuration: " << opt.config << "\n";
    }
  }
  if (const std::string note = swlio::daemon::VersionNote(opt.dir, swlio::daemon::SwlioVersion());
      !note.empty()) {
    std::cerr << "swlio-replay: " << note << "\n";
  }
  swlio::daemon::DaemonConfig config;
  if (!opt.config.empty()) {
    const auto loaded = swlio::daemon::LoadConfigFile(opt.config);
    if (!loaded.ok()) return std::cerr << loaded.ErrorReport(), 1;
    config = loaded.config;
  }
  std::string error;
  swlio::daemon::SensorInputOptions read;
  read.bag = swlio::tools::ToBagInputOptions(opt.bag);
  auto reader = swlio::daemon::OpenSensorInput(opt.dir, config.lidar, config.imu, read, &error);
  if (!reader) return std::cerr << "swlio-replay: " << error << "\n", 1;
  DdsOut dds;
  const bool publish = !opt.dds_config.empty();
  if (publish && !dds.Open(opt, &error)) return std::cerr << "swlio-replay: " << error << "\n", 1;
  std::ofstream tum(opt.out);
  if (!tum) return std::cerr << "swlio-replay: cannot write " << opt.out << "\n", 1;
  tum << "# timestamp tx ty tz qx qy qz qw  (IMU frame, host time, sweep end)\n";
  const Eigen::Isometry3d T_imu_lidar = swlio::daemon::ManifestExtrinsic(opt.dir).value_or(
      config.estimator.extrinsic_imu_lidar.ToIsometry());
  const auto setup =
      swlio::daemon::MakeEstimatorSetup(config, T_imu_lidar, swlio::daemon::ModeFromConfig(config));
  const swlio::daemon::TimeScale time = swlio::daemon::ManifestTimeScale(opt.dir);
  size_t sweeps = 0;
  swlio::daemon::EstimatorRunner runner(
      setup, nullptr, [&](const swlio::Scan&, const swlio::estimator::WindowResult& r) {
        ++sweeps;
        using swlio::estimator::OdometryStatus;
        const OdometryStatus st = r.odometry.status;
        if (st != OdometryStatus::kTracking && st != OdometryStatus::kMatchFailed) return;
        swlio::State host = r.odometry.state;  // stamps back on the host clock
        host.t_ns = time.ToHost(host.t_ns);
        swlio::daemon::WriteTumLine(tum, host);
        if (publish) dds.Sweep(host, r);
      });
  swlio::daemon::RecordingEvent e;
  int64_t first_event_ns = -1, wall_start_ns = 0;
  while (reader->Next(&e)) {
    const bool imu = e.kind == swlio::daemon::RecordingEvent::Kind::kImu;
    const int64_t t = imu ? e.imu.t_ns : e.scan.t_end_ns;
    if (!opt.deterministic) {  // pace: wait until this event's recorded time (× speed)
      if (first_event_ns < 0) first_event_ns = t, wall_start_ns = swlio::daemon::MonotonicNowNs();
      const auto due =
          wall_start_ns + static_cast<int64_t>(static_cast<double>(t - first_event_ns) / opt.speed);
      const int64_t wait = due - swlio::daemon::MonotonicNowNs();
      if (wait > 0) std::this_thread::sleep_for(std::chrono::nanoseconds(wait));
    }
    if (imu) {
      runner.AddImu(e.imu);
    } else {
      runner.AddScan(std::move(e.scan));
    }
  }
  const swlio::daemon::RecordingStats& s = reader->stats();
  std::cerr << reader->Report();
  std::printf(
      "{\"sweeps\": %zu, \"imu_samples\": %llu, \"lidar_packets\": %llu, \"missing_packets\": "
      "%llu, \"imu_checksum_errors\": %llu}\n",
      sweeps, static_cast<unsigned long long>(s.imu_samples),
      static_cast<unsigned long long>(s.lidar_packets),
      static_cast<unsigned long long>(s.missing_packets),
      static_cast<unsigned long long>(s.imu_checksum_errors));
  return 0;
}

int Main(int argc, char** argv) {
  CLI::App app{
      "swlio-replay: a recording or a ROS bag through the daemon's decoders, clocks and estimator"};
  Options opt;
  app.add_option("input", opt.dir,
                 "recording folder (lidar.pcap, imu.xbus, imu.rx.csv), or a ROS bag: rosbag2 "
                 "folder or .db3, .mcap, ROS 1 .bag")
      ->required()
      ->check(CLI::ExistingPath);
  swlio::tools::AddBagOptions(app, &opt.bag);
  app.add_option("--out", opt.out, "trajectory (TUM, IMU frame, sweep ends)")->required();
  app.add_option("--config", opt.config,
                 "swlio YAML (estimator options; ports from the manifest); default: the "
                 "recording's config.yaml (swliod recordings and incidents carry it)");
  app.add_option("--dds-config", opt.dds_config,
                 "publish odometry and path over DDS with this loopback-only Cyclone XML");
  app.add_option("--domain", opt.domain, "DDS domain id")->capture_default_str();
  app.add_option("--speed", opt.speed, "pacing: N× the recorded speed")
      ->check(CLI::Range(0.01, 1000.0))
      ->capture_default_str();
  app.add_flag("--deterministic", opt.deterministic,
               "no pacing, no clock reads: byte-identical output on every run");
  CLI11_PARSE(app, argc, argv);
  return Run(opt);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& ex) {
    std::cerr << "swlio-replay: " << ex.what() << "\n";
  } catch (...) {
    std::cerr << "swlio-replay: unknown error\n";
  }
  return 2;
}
