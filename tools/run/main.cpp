// swlio-run: runs the estimator offline on a recording folder (simulator output or a daemon
// recording) or a ROS bag through the same decoders and clock models as the daemon, and writes
// the IMU-frame trajectory in TUM format (stamped at each sweep's end, host time) and per-scan
// stage timings.

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "../common/bag_options.h"
#include "aux_sensors.h"
#include "localization_run.h"
#include "loop_closure_run.h"
#include "swlio/core/lie.h"
#include "swlio/daemon/config/config_loader.h"
#include "swlio/daemon/output/tum_output.h"
#include "swlio/daemon/pipeline/estimator_runner.h"
#include "swlio/daemon/recording/input_open.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/estimator/registration/lidar_odometry.h"
#include "swlio/estimator/window/window_estimator.h"

namespace {

using swlio::estimator::OdometryResult;
using swlio::estimator::OdometryStatus;

/// The window estimator's defaults (one object: temporaries of the large config per field made
/// GCC warn about maybe-uninitialized strings).
const swlio::estimator::WindowEstimatorConfig& WindowDefaults() {
  static const swlio::estimator::WindowEstimatorConfig defaults;
  return defaults;
}

struct Options {
  std::string loop_closure = "off", out_optimized, out_path, loops;
  std::string wheel = "off", gnss = "off", out_enu;  ///< optional sensors (aux_sensors.h)
  std::string time_offset = "on";      ///< window.time_offset: on (estimated), fixed, off
  double time_offset_init_ms = 0.0;    ///< window.time_offset.initial_offset_s (ms)
  std::string dynamic_removal = "on";  ///< moving objects out of the maps (visibility_image.h)
  std::string save_map, map_pcd, map;  ///< map files (loop closure writes, --localize reads)
  bool localize = false;
  std::string dir, out, timings, diagnostics, covariance, config, mode = "tightly-coupled";
  size_t window_size = WindowDefaults().window_size;
  int iterations = WindowDefaults().max_iterations;
  int reassociations = WindowDefaults().reassociations;
  double lidar_sigma_m = WindowDefaults().lidar_sigma_m;
  double bias_prior_acc = WindowDefaults().bias_prior_sigma_acc_mps2;
  double degenerate_eigenvalue = WindowDefaults().degenerate_eigenvalue;
  double floor_m = WindowDefaults().lidar_floor_sigma_m;
  double floor_tilt_rad = WindowDefaults().lidar_floor_sigma_tilt_rad;
  double floor_yaw_rad = WindowDefaults().lidar_floor_sigma_yaw_rad;
  bool estimate_extrinsic = false;
  std::vector<double> extrinsic_offset;  ///< dx dy dz (m) droll dpitch dyaw (deg)
  double start_s = 0.0;
  double end_s = 0.0;           ///< 0: to the end of the recording
  double calibrate_s = 0.0;     ///< window.calibrate_extrinsic_s (0: off)
  std::set<std::string> given;  ///< window flags present on the command line
  swlio::tools::BagCliOptions bag;
};

void WriteTimings(std::ostream& out, const OdometryResult& r, int64_t t_ns) {
  char line[256];
  std::snprintf(line, sizeof line, "%lld,%zu,%.4f,%.4f,%.4f,%.4f,%.4f",
                static_cast<long long>(t_ns), r.points_in, r.times.frontend_ms, r.times.match_ms,
                r.times.optimize_ms, r.times.total_ms, r.times.map_ms);
  out << line << '\n';
}

constexpr const char* kDiagnosticsHeader =
    "t_ns,status,converged,iterations,plane_inliers,edge_inliers,cost,"
    "hessian_eig_min,hessian_eig_max,degenerate_directions,planes,edges,uncovered,keyframe,"
    "vel_x,vel_y,vel_z,bias_acc_x,bias_acc_y,bias_acc_z,bias_gyro_x,bias_gyro_y,bias_gyro_z,"
    "time_offset_ms,time_offset_estimate_ms,time_offset_sigma_ms,window_time_offset_ms";

/// One line per sweep: what the registration reported (degeneracy: the smallest eigenvalue of
/// the 6×6 Gauss–Newton Hessian against the largest), then the state's velocity (world, m/s)
/// and biases (m/s², rad/s), then the LiDAR–IMU time offset applied, its estimate and σ (ms;
/// σ negative before the estimator has rows; time_offset_estimator.h), and the window's own
/// estimate (empty unless window_prior_sigma_s is set).
void WriteDiagnostics(std::ostream& out,
                      const OdometryResult& r,
                      const swlio::estimator::TimeOffsetStatus& offset,
                      int64_t t_ns) {
  char line[768];
  std::snprintf(line, sizeof line, "%lld,%s,%d,%d,%zu,%zu,%.6g,%.6g,%.6g,%d,%zu,%zu,%zu,%d",
                static_cast<long long>(t_ns), swlio::estimator::ToString(r.status),
                r.match.converged ? 1 : 0, r.match.iterations, r.match.plane_inliers,
                r.match.edge_inliers, r.match.cost, r.match.hessian_eigenvalues(0),
                r.match.hessian_eigenvalues(5), r.match.degenerate_directions, r.planes, r.edges,
                r.points_uncovered, r.keyframe ? 1 : 0);
  out << line;
  const swlio::State& x = r.state;
  std::snprintf(line, sizeof line, ",%.5f,%.5f,%.5f,%.6f,%.6f,%.6f,%.7f,%.7f,%.7f", x.vel_world.x(),
                x.vel_world.y(), x.vel_world.z(), x.bias_acc.x(), x.bias_acc.y(), x.bias_acc.z(),
                x.bias_gyro.x(), x.bias_gyro.y(), x.bias_gyro.z());
  out << line;
  std::snprintf(line, sizeof line, ",%.4f,%.4f,%.4f,", offset.offset_s * 1e3,
                offset.estimate_s * 1e3, offset.sigma_s < 0.0 ? -1.0 : offset.sigma_s * 1e3);
  out << line;
  if (offset.window_offset_s) {
    std::snprintf(line, sizeof line, "%.4f", *offset.window_offset_s * 1e3);
    out << line;
  }
  out << '\n';
}

/// Header of --covariance: the newest state and its marginal covariance P (state_covariance.h:
/// [δp_world, δθ_world, δv_world, δb_a, δb_g]), upper triangle row by row; then the map's tilt
/// against gravity [θx, θy] (WindowResult::gravity_tilt_rad, zero unless estimated) and the
/// covariance of the attitude against gravity (StateCovariance::rot_gravity), upper triangle.
std::string CovarianceHeader() {
  std::string h = "t_ns,px,py,pz,qx,qy,qz,qw,vx,vy,vz";
  for (int i = 0; i < swlio::estimator::kStateCovSize; ++i) {
    for (int j = i; j < swlio::estimator::kStateCovSize; ++j) {
      h += ",P_" + std::to_string(i) + "_" + std::to_string(j);
    }
  }
  h += ",tilt_x,tilt_y";
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) h += ",Pg_" + std::to_string(i) + "_" + std::to_string(j);
  }
  return h;
}

void WriteCovariance(std::ostream& out,
                     const swlio::State& x,
                     const swlio::estimator::StateCovariance& c,
                     const Eigen::Vector2d& gravity_tilt_rad) {
  const Eigen::Quaterniond q = swlio::lie::PositiveW(Eigen::Quaterniond(x.T_world_imu.linear()));
  const Eigen::Vector3d p = x.T_world_imu.translation();
  char field[64];
  std::snprintf(field, sizeof field, "%lld", static_cast<long long>(x.t_ns));
  out << field;
  for (const double v : {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w(), x.vel_world.x(),
                         x.vel_world.y(), x.vel_world.z()}) {
    std::snprintf(field, sizeof field, ",%.9g", v);
    out << field;
  }
  for (int i = 0; i < swlio::estimator::kStateCovSize; ++i) {
    for (int j = i; j < swlio::estimator::kStateCovSize; ++j) {
      std::snprintf(field, sizeof field, ",%.6e", c.P(i, j));
      out << field;
    }
  }
  std::snprintf(field, sizeof field, ",%.9g,%.9g", gravity_tilt_rad.x(), gravity_tilt_rad.y());
  out << field;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      std::snprintf(field, sizeof field, ",%.6e", c.rot_gravity(i, j));
      out << field;
    }
  }
  out << '\n';
}

/// Running means for the summary line.
struct Summary {
  size_t scans = 0, tracked = 0, failed = 0, skipped = 0, reinitializations = 0;
  size_t wheel_factors = 0, wheel_rejected = 0;  ///< the window's counts (--wheel on)
  size_t standstill = 0;  ///< sweeps the window took for rest (zero-velocity factor)
  uint64_t lidar_clock_jumps = 0, imu_clock_jumps = 0;  ///< the clock models' restarts
  bool wheel = false;
  swlio::estimator::TimeOffsetStatus time_offset;  ///< the window's, at the last sweep
  double total_ms = 0.0, planes = 0.0, edges = 0.0, inliers = 0.0, iterations = 0.0;
  std::string extra;  ///< more JSON members (loop closure), or empty

  void Add(const OdometryResult& r) {
    ++scans;
    skipped += r.status == OdometryStatus::kSkipped ? 1 : 0;
    if (r.status == OdometryStatus::kInitializing || r.status == OdometryStatus::kSkipped) return;
    (r.status == OdometryStatus::kTracking ? tracked : failed)++;
    total_ms += r.times.total_ms;
    planes += static_cast<double>(r.planes);
    edges += static_cast<double>(r.edges);
    inliers += static_cast<double>(r.match.plane_inliers + r.match.edge_inliers);
    iterations += r.match.iterations;
  }
  std::string WheelJson() const {
    if (!wheel) return "";
    char json[128];
    std::snprintf(json, sizeof json, ", \"wheel\": {\"factors\": %zu, \"rejected\": %zu}",
                  wheel_factors, wheel_rejected);
    return json;
  }
  /// The LiDAR–IMU time offset (tightly coupled mode with estimator.window.time_offset on).
  std::string TimeOffsetJson() const {
    if (!time_offset.enabled) return "";
    char json[256];
    std::snprintf(json, sizeof json,
                  ", \"time_offset\": {\"applied_ms\": %.4f, \"estimate_ms\": %.4f, "
                  "\"sigma_ms\": %.4f, \"excitation_radps\": %.4f, \"rows\": %zu, "
                  "\"updates\": %zu",
                  time_offset.offset_s * 1e3, time_offset.estimate_s * 1e3,
                  time_offset.sigma_s < 0.0 ? -1.0 : time_offset.sigma_s * 1e3,
                  time_offset.excitation_radps, time_offset.rows, time_offset.updates);
    std::string out = json;
    if (time_offset.window_offset_s) {
      std::snprintf(json, sizeof json, ", \"window_ms\": %.4f", *time_offset.window_offset_s * 1e3);
      out += json;
    }
    return out + "}";
  }
  void Print() const {
    const double n = std::max<double>(1.0, static_cast<double>(tracked + failed));
    std::printf(
        "{\"scans\": %zu, \"tracked\": %zu, \"match_failed\": %zu, \"skipped\": %zu, "
        "\"mean_scan_ms\": %.2f, "
        "\"mean_planes\": %.0f, \"mean_edges\": %.0f, \"mean_inliers\": %.0f, "
        "\"mean_iterations\": %.2f, \"reinitializations\": %zu, \"standstill_sweeps\": "
        "%zu, \"clock_jumps\": {\"lidar\": %llu, \"imu\": %llu}%s%s%s%s}\n",
        scans, tracked, failed, skipped, total_ms / n, planes / n, edges / n, inliers / n,
        iterations / n, reinitializations, standstill,
        static_cast<unsigned long long>(lidar_clock_jumps),
        static_cast<unsigned long long>(imu_clock_jumps), WheelJson().c_str(),
        TimeOffsetJson().c_str(), extra.empty() ? "" : ", ", extra.c_str());
  }
};

/// A sensor clock that jumped mis-times the data around the jump; the estimator's divergence
/// that may follow would otherwise be the only sign (the daemon's health warns the same way).
void WarnClockJumps(const swlio::daemon::RecordingStats& stats) {
  auto warn = [](const char* sensor, const swlio::drivers::ClockModelStats& clock) {
    if (clock.jumps == 0) return;
    std::cerr << "swlio-run: the " << sensor << " clock jumped " << clock.jumps
              << " time(s) in this recording (offset now " << std::fixed << std::setprecision(3)
              << clock.offset_ns * 1e-9 << std::defaultfloat
              << " s): its time was stepped, or it does not run at the receive clock's rate; data "
                 "across a jump is mis-timed\n";
  };
  warn("LiDAR", stats.lidar_clock);
  warn("IMU", stats.imu_clock);
}

/// The daemon configuration (defaults without --config); false with a report on errors.
bool LoadDaemonConfig(const Options& opt, swlio::daemon::DaemonConfig* config) {
  if (opt.config.empty()) return true;
  const swlio::daemon::LoadedConfig loaded = swlio::daemon::LoadConfigFile(opt.config);
  if (!loaded.ok()) {
    std::cerr << loaded.ErrorReport();
    return false;
  }
  *config = loaded.config;
  return true;
}

/// The window flags given on the command line override the configuration file.
void ApplyWindowFlags(const Options& opt, swlio::estimator::WindowEstimatorConfig* w) {
  auto given = [&](const char* flag) { return opt.given.count(flag) != 0; };
  if (given("--window-size")) w->window_size = opt.window_size;
  if (given("--time-offset")) {
    w->time_offset.enabled = opt.time_offset != "off";
    w->time_offset.estimate = opt.time_offset == "on";
  }
  if (given("--time-offset-init-ms"))
    w->time_offset.initial_offset_s = opt.time_offset_init_ms * 1e-3;
  if (given("--calibrate-extrinsic")) w->calibrate_extrinsic_s = opt.calibrate_s;
  if (given("--iterations")) w->max_iterations = opt.iterations;
  if (given("--reassociations")) w->reassociations = opt.reassociations;
  if (given("--lidar-sigma")) w->lidar_sigma_m = opt.lidar_sigma_m;
  if (given("--bias-prior-acc")) w->bias_prior_sigma_acc_mps2 = opt.bias_prior_acc;
  if (given("--estimate-extrinsic")) w->estimate_extrinsic = opt.estimate_extrinsic;
  if (given("--degenerate-eigenvalue")) w->degenerate_eigenvalue = opt.degenerate_eigenvalue;
  if (given("--lidar-floor-m")) w->lidar_floor_sigma_m = opt.floor_m;
  if (given("--lidar-floor-tilt")) w->lidar_floor_sigma_tilt_rad = opt.floor_tilt_rad;
  if (given("--lidar-floor-yaw")) w->lidar_floor_sigma_yaw_rad = opt.floor_yaw_rad;
}

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

/// The extrinsic at the end, and how far it is from the one the recording or config gave
/// (the truth for simulator recordings, which is what --extrinsic-offset perturbs).
void PrintExtrinsic(const Eigen::Isometry3d& T_final, const Eigen::Isometry3d& T_given) {
  const Eigen::Isometry3d d = T_given.inverse() * T_final;
  const Eigen::Quaterniond q(T_final.linear());
  std::printf(
      "{\"extrinsic_T_imu_lidar\": {\"translation_m\": [%.4f, %.4f, %.4f], "
      "\"quaternion_xyzw\": [%.6f, %.6f, %.6f, %.6f]}, \"from_given_translation_m\": %.4f, "
      "\"from_given_rotation_deg\": %.3f}\n",
      T_final.translation().x(), T_final.translation().y(), T_final.translation().z(), q.x(), q.y(),
      q.z(), q.w(), d.translation().norm(), Eigen::AngleAxisd(d.linear()).angle() * kRadToDeg);
}

/// The online calibration's outcome: its result against the given extrinsic (see above), or
/// how often it was tried and why it was refused.
void PrintCalibration(const swlio::estimator::WindowEstimator& window,
                      const Eigen::Isometry3d& T_given) {
  const swlio::estimator::ExtrinsicCalibration* c = window.calibration();
  if (c == nullptr) {
    const auto* run = window.calibration_run();
    std::printf(
        "{\"extrinsic_calibration\": {\"ok\": false, \"attempts\": %d, \"message\": \"%s\"}}\n",
        run ? run->attempts() : 0,
        run && !run->last_message().empty() ? run->last_message().c_str()
                                            : "not enough motion recorded");
    return;
  }
  const Eigen::Isometry3d d = T_given.inverse() * c->T_imu_lidar;
  const Eigen::Matrix<double, 6, 1> sigma = c->covariance.diagonal().cwiseSqrt();
  std::printf(
      "{\"extrinsic_calibration\": {\"ok\": true, \"sigma_translation_m\": [%.4f, %.4f, %.4f], "
      "\"sigma_rotation_deg\": [%.3f, %.3f, %.3f], \"pose_sigma_scale\": %.2f, "
      "\"correlation_poses\": %.1f, \"position_rms_m\": %.4f, \"rotation_rms_deg\": %.3f}, "
      "\"from_given_translation_m\": %.4f, "
      "\"from_given_rotation_deg\": %.3f}\n",
      sigma(0), sigma(1), sigma(2), sigma(3) * kRadToDeg, sigma(4) * kRadToDeg,
      sigma(5) * kRadToDeg, c->pose_sigma_scale, c->correlation_poses, c->position_rms_m,
      c->rotation_rms_rad * kRadToDeg, d.translation().norm(),
      Eigen::AngleAxisd(d.linear()).angle() * kRadToDeg);
}

int Run(const Options& opt) {
  swlio::daemon::DaemonConfig daemon_config;
  if (!LoadDaemonConfig(opt, &daemon_config)) return 1;
  const auto manifest_extrinsic = swlio::daemon::ManifestExtrinsic(opt.dir);
  swlio::estimator::LidarOdometryConfig config = swlio::estimator::MakeOdometryConfig(
      daemon_config.estimator,
      manifest_extrinsic.value_or(daemon_config.estimator.extrinsic_imu_lidar.ToIsometry()));
  const Eigen::Isometry3d T_imu_lidar_given = config.T_imu_lidar;
  if (opt.extrinsic_offset.size() == 6) {
    const auto& o = opt.extrinsic_offset;
    constexpr double kDeg = 3.14159265358979323846 / 180.0;
    config.T_imu_lidar.translation() += Eigen::Vector3d(o[0], o[1], o[2]);
    config.T_imu_lidar.linear() =
        config.T_imu_lidar.linear() * (Eigen::AngleAxisd(o[5] * kDeg, Eigen::Vector3d::UnitZ()) *
                                       Eigen::AngleAxisd(o[4] * kDeg, Eigen::Vector3d::UnitY()) *
                                       Eigen::AngleAxisd(o[3] * kDeg, Eigen::Vector3d::UnitX()))
                                          .toRotationMatrix();
  }
  if (!manifest_extrinsic && opt.config.empty()) {
    std::cerr << "swlio-run: no extrinsic in " << opt.dir
              << (swlio::daemon::IsRecordingFolder(opt.dir) ? "/manifest.yaml" : "")
              << " and no --config; using identity\n";
  }
  std::string error;
  // --wheel / --gnss win over the configuration's switches (both off by default).
  const bool wheel =
      opt.given.count("--wheel") > 0 ? opt.wheel == "on" : daemon_config.window.wheel.enabled;
  const bool gnss =
      opt.given.count("--gnss") > 0 ? opt.gnss == "on" : daemon_config.loop_closure.gnss.enabled;
  daemon_config.window.wheel.enabled = false;
  daemon_config.loop_closure.gnss.enabled = false;
  swlio::daemon::SensorInputOptions read;
  read.bag = swlio::tools::ToBagInputOptions(opt.bag);
  if (!swlio::tools::SetUpAuxSensors(opt.dir, wheel, gnss, &daemon_config, &read, &error)) {
    std::cerr << "swlio-run: " << error << "\n";
    return 1;
  }
  auto reader =
      swlio::daemon::OpenSensorInput(opt.dir, daemon_config.lidar, daemon_config.imu, read, &error);
  if (!reader) {
    std::cerr << "swlio-run: " << error << "\n";
    return 1;
  }
  // A daemon recording made at --time-scale N has its receive times stretched onto the sensors'
  // time base (time_scale.h): the estimator runs on it, and every output goes back to host
  // time, as the daemon published it (the live simulator's ground truth is on host time too).
  const swlio::daemon::TimeScale time = swlio::daemon::ManifestTimeScale(opt.dir);
  const auto host = [&time](swlio::State s) {
    s.t_ns = time.ToHost(s.t_ns);
    return s;
  };
  std::ofstream tum(opt.out);
  std::ofstream timings, diagnostics, covariance;
  if (!opt.timings.empty()) timings.open(opt.timings);
  if (!opt.diagnostics.empty()) diagnostics.open(opt.diagnostics);
  if (!opt.covariance.empty()) covariance.open(opt.covariance);
  for (const auto& [stream, path] :
       {std::pair<const std::ofstream*, const std::string*>{&tum, &opt.out},
        {&timings, &opt.timings},
        {&diagnostics, &opt.diagnostics},
        {&covariance, &opt.covariance}}) {
    if (!path->empty() && !*stream) {
      std::cerr << "swlio-run: cannot write " << *path << "\n";
      return 1;
    }
  }
  tum << "# timestamp tx ty tz qx qy qz qw  (IMU frame, host time, sweep end)\n";
  if (timings) timings << "t_ns,points,frontend_ms,match_ms,optimize_ms,total_ms,map_ms\n";
  if (diagnostics) diagnostics << kDiagnosticsHeader << '\n';
  if (covariance) covariance << CovarianceHeader() << '\n';

  // The window's options: the configuration file's estimator.window (struct defaults without
  // --config), then the command-line flags that were given.
  swlio::estimator::WindowEstimatorConfig window_config = daemon_config.window;
  window_config.odometry = config;
  ApplyWindowFlags(opt, &window_config);
  if (opt.given.count("--dynamic-removal") > 0) {
    window_config.visibility.enabled = opt.dynamic_removal == "on";
    daemon_config.loop_closure.visibility.enabled = opt.dynamic_removal == "on";
  }
  if (const auto issues = window_config.Validate(); !issues.empty()) {
    for (const auto& issue : issues)
      std::cerr << "swlio-run: " << issue.key << ": " << issue.reason << "\n";
    return 1;
  }
  const bool tightly_coupled = opt.mode == "tightly-coupled";
  swlio::daemon::EstimatorSetup setup;
  setup.mode = tightly_coupled ? swlio::daemon::EstimatorMode::kTightlyCoupled
                               : swlio::daemon::EstimatorMode::kLidarOnly;
  setup.odometry = config;
  setup.window = window_config;
  Summary summary;
  summary.wheel = window_config.wheel.enabled && tightly_coupled;
  std::unique_ptr<swlio::tools::LoopClosureRun> loops;
  // --loop-closure wins over the configuration's estimator.loop_closure.enabled (on by
  // default, and then off in lidar-only mode, which makes no keyframes for it).
  const bool asked = opt.given.count("--loop-closure") > 0;
  if ((asked && opt.loop_closure == "on") && !tightly_coupled) {
    std::cerr << "swlio-run: --loop-closure on needs --mode tightly-coupled\n";
    return 1;
  }
  if (opt.localize && !tightly_coupled) {
    std::cerr << "swlio-run: --localize needs --mode tightly-coupled\n";
    return 1;
  }
  const bool loop_closure =
      asked ? opt.loop_closure == "on" : daemon_config.loop_closure.enabled && tightly_coupled;
  if (gnss && (!tightly_coupled || opt.localize)) {
    std::cerr << "swlio-run: --gnss on needs --mode tightly-coupled, without --localize\n";
    return 1;
  }
  daemon_config.loop_closure.enabled = loop_closure;  // off: the graph runs for GNSS alone
  std::unique_ptr<swlio::tools::LocalizationRun> localization;
  if (opt.localize) {
    swlio::estimator::LocalizationConfig lc = daemon_config.localization;  // --config's
    lc.registration = daemon_config.loop_closure;
    localization =
        swlio::tools::LocalizationRun::Open(opt.map, lc, &swlio::daemon::ThreadCpuNowNs, &error);
    if (!localization) {
      std::cerr << "swlio-run: " << error << "\n";
      return 1;
    }
  } else if (loop_closure || gnss) {
    loops = std::make_unique<swlio::tools::LoopClosureRun>(daemon_config.loop_closure,
                                                           &swlio::daemon::ThreadCpuNowNs, time);
  } else if (!opt.save_map.empty() || !opt.out_optimized.empty() || !opt.out_path.empty()) {
    std::cerr << "swlio-run: --save-map, --out-optimized and --out-path need loop closure (the "
                 "pose graph)\n";
    return 1;
  }
  auto process = [&](const swlio::Scan& scan, const swlio::estimator::WindowResult& w) {
    const OdometryResult& r = w.odometry;
    if (covariance && w.covariance.valid)
      WriteCovariance(covariance, host(r.state), w.covariance, w.gravity_tilt_rad);
    summary.Add(r);
    summary.reinitializations = w.reinitializations;  // the estimator's count
    summary.wheel_factors = std::max(summary.wheel_factors, w.wheel_factors);
    summary.wheel_rejected = std::max(summary.wheel_rejected, w.wheel_rejected);
    summary.standstill = std::max(summary.standstill, w.standstill_frames);
    if (w.time_offset.enabled) summary.time_offset = w.time_offset;
    if (w.diverged != swlio::estimator::DivergenceReason::kNone) {
      std::cerr << "swlio-run: sweep ending at " << static_cast<double>(scan.t_end_ns) * 1e-9
                << " s: " << swlio::estimator::ToString(w.diverged) << ", re-initializing\n";
    }
    if (timings) WriteTimings(timings, r, time.ToHost(scan.t_end_ns));
    if (diagnostics) WriteDiagnostics(diagnostics, r, w.time_offset, time.ToHost(scan.t_end_ns));
    if (r.status != OdometryStatus::kTracking && r.status != OdometryStatus::kMatchFailed) return;
    if (localization) {
      if (swlio::State s; localization->OnSweep(r.state, w.keyframe.get(), &s))
        swlio::daemon::WriteTumLine(tum, host(s));
      return;
    }
    swlio::daemon::WriteTumLine(tum,
                                host(loops ? loops->OnSweep(r.state, w.keyframe.get()) : r.state));
  };
  swlio::daemon::EstimatorRunner runner(setup, &swlio::daemon::ThreadCpuNowNs, process);
  swlio::daemon::RecordingEvent e;
  // --start-s: the estimator sees nothing before that many seconds into the recording (the
  // decoders and clock models do: as a daemon started while the robot is already driving).
  int64_t start_ns = -1;
  while (reader->Next(&e)) {
    const int64_t t_ns = e.t_ns();
    if (start_ns < 0) {
      start_ns = t_ns + static_cast<int64_t>(opt.start_s * 1e9);
      if (localization) localization->SetStart(t_ns);
    }
    if (t_ns < start_ns) continue;
    if (opt.end_s > 0.0 && t_ns >= start_ns + static_cast<int64_t>((opt.end_s - opt.start_s) * 1e9))
      break;
    switch (e.kind) {
      case swlio::daemon::RecordingEvent::Kind::kImu:
        runner.AddImu(e.imu);
        break;
      case swlio::daemon::RecordingEvent::Kind::kScan:
        runner.AddScan(std::move(e.scan));
        break;
      case swlio::daemon::RecordingEvent::Kind::kWheel:
        runner.AddWheel(e.wheel);
        break;
      case swlio::daemon::RecordingEvent::Kind::kGnss:
        if (loops) loops->OnGnss(e.gnss);
        break;
    }
  }
  // Sweeps the IMU stream never covered (the recording's last ones) are not processed.
  if (runner.waiting() > 0)
    std::cerr << "swlio-run: " << runner.waiting()
              << " last sweep(s) without IMU coverage not processed\n";
  if (loops) {
    summary.extra = loops->SummaryJson();
    if (!opt.out_optimized.empty() && !loops->WriteOptimized(opt.out_optimized)) {
      std::cerr << "swlio-run: cannot write " << opt.out_optimized << "\n";
      return 1;
    }
    if (!opt.out_path.empty() && !loops->WritePath(opt.out_path)) {
      std::cerr << "swlio-run: cannot write " << opt.out_path << "\n";
      return 1;
    }
    if (!opt.loops.empty() && !loops->WriteLoops(opt.loops)) {
      std::cerr << "swlio-run: cannot write " << opt.loops << "\n";
      return 1;
    }
    if (!opt.out_enu.empty() && !loops->WriteEnu(opt.out_enu, &error)) {
      std::cerr << "swlio-run: --out-enu: " << error << "\n";
      return 1;
    }
    if (!opt.save_map.empty() && !loops->SaveMap(opt.save_map, opt.map_pcd, &error)) {
      std::cerr << "swlio-run: " << error << "\n";
      return 1;
    }
  }
  if (localization) summary.extra = localization->SummaryJson();
  summary.lidar_clock_jumps = reader->stats().lidar_clock.jumps;
  summary.imu_clock_jumps = reader->stats().imu_clock.jumps;
  WarnClockJumps(reader->stats());
  std::cerr << reader->Report();
  summary.Print();
  if (tightly_coupled && window_config.calibrate_extrinsic_s > 0.0) {
    PrintCalibration(*runner.window(), T_imu_lidar_given);
  }
  if (tightly_coupled && (window_config.estimate_extrinsic || !opt.extrinsic_offset.empty() ||
                          window_config.calibrate_extrinsic_s > 0.0)) {
    PrintExtrinsic(runner.window()->T_imu_lidar(), T_imu_lidar_given);
  }
  return 0;
}

int Main(int argc, char** argv) {
  CLI::App app{"swlio-run: the estimator offline on a recording folder or a ROS bag"};
  Options opt;
  app.add_option("input", opt.dir,
                 "recording folder (lidar.pcap, imu.xbus, imu.rx.csv), or a ROS bag: rosbag2 "
                 "folder or .db3, .mcap, ROS 1 .bag")
      ->required();
  swlio::tools::AddBagOptions(app, &opt.bag);
  app.add_option("--mode", opt.mode, "estimator mode")
      ->check(CLI::IsMember({"tightly-coupled", "lidar-only"}))
      ->capture_default_str();
  app.add_option("--window-size", opt.window_size, "frames in the sliding window (tightly-coupled)")
      ->capture_default_str();
  app.add_option("--iterations", opt.iterations, "solver iterations per solve (tightly-coupled)")
      ->capture_default_str();
  app.add_option("--reassociations", opt.reassociations,
                 "re-associations (and solves) of the newest frame per sweep (tightly-coupled)")
      ->capture_default_str();
  app.add_option("--lidar-sigma", opt.lidar_sigma_m,
                 "point-to-plane/line standard deviation, m (tightly-coupled)")
      ->capture_default_str();
  app.add_option("--bias-prior-acc", opt.bias_prior_acc,
                 "weak prior on every frame's accelerometer bias, m/s² (0: none; tightly-coupled)")
      ->capture_default_str();
  app.add_option("--degenerate-eigenvalue", opt.degenerate_eigenvalue,
                 "LiDAR Hessian eigenvalue below which a direction is left to the IMU "
                 "(tightly-coupled)")
      ->capture_default_str();
  app.add_option("--lidar-floor-m", opt.floor_m,
                 "floor under a sweep's LiDAR position standard deviation, m (tightly-coupled)")
      ->capture_default_str();
  app.add_option("--lidar-floor-tilt", opt.floor_tilt_rad,
                 "floor under a sweep's LiDAR roll/pitch standard deviation, rad (tightly-coupled)")
      ->capture_default_str();
  app.add_option("--lidar-floor-yaw", opt.floor_yaw_rad,
                 "floor under a sweep's LiDAR yaw standard deviation, rad (tightly-coupled)")
      ->capture_default_str();
  app.add_option("--start-s", opt.start_s,
                 "skip this many seconds at the start of the recording (a start while moving)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--end-s", opt.end_s,
                 "stop this many seconds into the recording (0: at its end), e.g. to profile a "
                 "stretch of it")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--extrinsic-offset", opt.extrinsic_offset,
                 "perturb the given extrinsic: dx dy dz (m) droll dpitch dyaw (deg), e.g. to test "
                 "--estimate-extrinsic")
      ->expected(6);
  app.add_option("--calibrate-extrinsic", opt.calibrate_s,
                 "calibrate T_imu_lidar online once this many seconds of LiDAR-only odometry "
                 "(beside the window) are in, in one batch with the IMU, and restart the window "
                 "on it; needs turns, retried until they determine the rotation "
                 "(tightly-coupled; extrinsic_calibration_run.h)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--time-offset", opt.time_offset,
                 "the LiDAR-IMU time offset applied to the IMU samples: on (estimated online, "
                 "the default), fixed (--time-offset-init-ms), off (tightly-coupled; "
                 "estimator.window.time_offset.enabled and .estimate)")
      ->check(CLI::IsMember({"on", "fixed", "off"}));
  app.add_option("--time-offset-init-ms", opt.time_offset_init_ms,
                 "the time offset to start from (ms; > 0: the IMU's stamps are late; "
                 "estimator.window.time_offset.initial_offset_s)");
  app.add_flag("--estimate-extrinsic", opt.estimate_extrinsic,
               "refine T_imu_lidar online (tightly-coupled; weak prior on the configured value)");
  app.add_option("--out", opt.out,
                 "trajectory (TUM, IMU frame; with loop closure each sweep with the correction "
                 "known at its time, as published)")
      ->required();
  app.add_option(
         "--loop-closure", opt.loop_closure,
         "loop closure and pose graph (tightly-coupled); absent: estimator.loop_closure.enabled "
         "of --config, on by default")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_option("--dynamic-removal", opt.dynamic_removal,
                 "moving objects out of the local and saved maps by what later sweeps see "
                 "through (estimator.window.visibility, estimator.loop_closure.visibility)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--wheel", opt.wheel,
                 "wheel odometry from the recording's can.log (a bag: its Odometry or "
                 "TwistStamped topic) as a velocity factor (tightly-coupled; "
                 "estimator.window.wheel; the manifest's wheel: block gives the CAN layout and "
                 "the base frame, else --config's can: section and T_imu_base)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--gnss", opt.gnss,
                 "GNSS fixes from imu.xbus (GnssPvtData; a bag: its NavSatFix topic) as position "
                 "factors in the pose graph (estimator.loop_closure.gnss; the manifest's gnss: "
                 "block gives the ENU origin and the lever arm, else --config); runs the graph "
                 "even with --loop-closure off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--out-enu", opt.out_enu,
                 "with --gnss on: every sweep corrected by the final graph, in the local ENU "
                 "frame (TUM)");
  app.add_option("--out-optimized", opt.out_optimized,
                 "with loop closure: every sweep corrected by the final pose graph (TUM)");
  app.add_option("--out-path", opt.out_path,
                 "with loop closure: the final pose graph's nodes (TUM; the keyframe path the "
                 "daemon publishes last)");
  app.add_option("--loops", opt.loops,
                 "with loop closure: every verified loop candidate (CSV: times of both nodes, "
                 "verdict, fitness, inliers, Hessian's smallest eigenvalue, correction, relative "
                 "pose)");
  app.add_option("--save-map", opt.save_map,
                 "with loop closure: save the final graph as a map (estimator/map-format.md), for "
                 "--localize");
  app.add_option("--map-pcd", opt.map_pcd,
                 "with --save-map: also the merged cloud of the map as PCD, for viewers");
  app.add_option("--map", opt.map, "a saved map (--save-map) to localize in");
  app.add_flag("--localize", opt.localize,
               "localize in --map: global relocalization from place descriptors, then tracking "
               "against the fixed map; --out gets the sweeps from the first localized one on, "
               "in the map's frame")
      ->needs("--map");
  app.add_option("--timings", opt.timings,
                 "per-scan stage timings CSV (t_ns,points,frontend_ms,match_ms,optimize_ms,"
                 "total_ms,map_ms; thread CPU time, 0 for a stage that did not run; map_ms: a "
                 "keyframe's map upkeep, in total_ms)");
  app.add_option("--covariance", opt.covariance,
                 "per-sweep state and its marginal covariance CSV (tightly coupled mode; "
                 "see state_covariance.h for the order)");
  app.add_option("--diagnostics", opt.diagnostics,
                 "per-scan registration CSV (status, convergence, iterations, inliers, cost, "
                 "Hessian eigenvalues, feature counts, keyframe)");
  app.add_option("--config", opt.config,
                 "daemon configuration (swlio.yaml): sensors, estimator, estimator.window (the "
                 "flags above override it), extrinsic (a manifest's extrinsic wins)");
  CLI11_PARSE(app, argc, argv);
  for (const char* flag :
       {"--window-size", "--iterations", "--reassociations", "--lidar-sigma", "--bias-prior-acc",
        "--estimate-extrinsic", "--degenerate-eigenvalue", "--calibrate-extrinsic",
        "--lidar-floor-m", "--lidar-floor-tilt", "--lidar-floor-yaw", "--loop-closure", "--wheel",
        "--gnss", "--time-offset", "--time-offset-init-ms", "--dynamic-removal"}) {
    if (app.count(flag) > 0) opt.given.insert(flag);
  }
  return Run(opt);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "swlio-run: " << e.what() << "\n";
  } catch (...) {
    std::cerr << "swlio-run: unknown error\n";
  }
  return 2;
}
