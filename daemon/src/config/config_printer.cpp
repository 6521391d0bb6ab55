// `swliod --print-config`: a DaemonConfig written back as the YAML the loader reads. With
// config_loader.cpp the only file that includes yaml-cpp (here only its emitter); the two are
// kept in step by the round-trip tests (tests/daemon/config/config_printer_test.cpp): print, load,
// print again gives the same text, and the keys printed are the shipped file's.
//
// Keys follow config/swlio.yaml's order. Each Emit() below mirrors one Bind() of the loader.

#include "swlio/daemon/config/config_printer.h"

#include <yaml-cpp/yaml.h>

#include <array>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <string>
#include <utility>

namespace swlio::daemon {
namespace {

/// The shortest text that reads back as the same double (std::to_chars), with ".0" on whole
/// numbers so that a real-valued key shows as one.
std::string NumberText(double v) {
  std::array<char, 32> buffer{};
  const auto [end, ec] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  std::string text(buffer.data(), ec == std::errc() ? end : buffer.data());
  if (text.find_first_of(".en") == std::string::npos) text += ".0";  // e: 1e+20, n: nan, inf
  return text;
}

/// One YAML mapping at a time, as the loader's Section reads it.
class ConfigWriter {
 public:
  void Put(const char* key, bool v) { out_ << YAML::Key << key << YAML::Value << v; }
  void Put(const char* key, double v) { out_ << YAML::Key << key << YAML::Value << NumberText(v); }
  void Put(const char* key, const std::string& v) { out_ << YAML::Key << key << YAML::Value << v; }
  template <std::integral Int>
  void Put(const char* key, Int v) {
    out_ << YAML::Key << key << YAML::Value << static_cast<int64_t>(v);
  }
  /// CAN identifiers, as the DBC files and candump write them.
  void PutHex(const char* key, int64_t v) {
    out_ << YAML::Key << key << YAML::Value << YAML::Hex << v;
  }
  template <size_t N>
  void Put(const char* key, const std::array<double, N>& v) {
    out_ << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const double x : v) out_ << NumberText(x);
    out_ << YAML::EndSeq;
  }
  void Comment(const std::string& text) { out_ << YAML::Comment(text); }

  /// A nested mapping under `key` (BeginMap(nullptr): a list item); closed by EndMap().
  void BeginMap(const char* key, bool flow = false) {
    if (key != nullptr) out_ << YAML::Key << key << YAML::Value;
    if (flow) out_ << YAML::Flow;
    out_ << YAML::BeginMap;
  }
  void EndMap() { out_ << YAML::EndMap; }
  /// A list under `key` (`[]` when `empty`); closed by EndList().
  void BeginList(const char* key, bool empty) {
    out_ << YAML::Key << key << YAML::Value;
    if (empty) out_ << YAML::Flow;
    out_ << YAML::BeginSeq;
  }
  void EndList() { out_ << YAML::EndSeq; }

  std::string Text() const { return std::string(out_.c_str()) + "\n"; }

 private:
  YAML::Emitter out_;
};

void Emit(ConfigWriter& w, const drivers::LidarConfig& c) {
  w.BeginMap("lidar");
  w.Put("model", c.model);
  w.Put("bind_address", c.bind_address);
  w.Put("msop_port", c.msop_port);
  w.Put("difop_port", c.difop_port);
  w.Put("cut_angle_deg", c.cut_angle_deg);
  w.Put("min_range_m", c.min_range_m);
  w.Put("max_range_m", c.max_range_m);
  w.Put("rcvbuf_bytes", c.rcvbuf_bytes);
  w.Put("rx_batch_ms", c.rx_batch_ms);
  w.Put("vertical_angles_deg", c.vertical_angles_deg);
  w.Put("rpm", c.rpm);
  w.Put("lens_offset_m", c.EffectiveLensOffsetM());  // when absent, the model's vendor value
  w.EndMap();
}

void Emit(ConfigWriter& w, const drivers::ImuConfig& c) {
  w.BeginMap("imu");
  w.Put("device", c.device);
  w.Put("baud", c.baud);
  w.Put("output_rate_hz", c.output_rate_hz);
  w.Put("configure_on_start", c.configure_on_start);
  w.Put("reply_timeout_ms", c.reply_timeout_ms);
  w.Put("configure_retries", c.configure_retries);
  w.EndMap();
}

/// start_bit or byte_offset, whichever is given (-1: not given).
void Emit(ConfigWriter& w, const drivers::CanSignalConfig& c) {
  w.BeginMap(nullptr);
  w.Put("role", c.role);
  w.PutHex("can_id", c.can_id);
  w.Put("extended", c.extended);
  if (c.start_bit >= 0) w.Put("start_bit", c.start_bit);
  if (c.byte_offset >= 0) w.Put("byte_offset", c.byte_offset);
  w.Put("length_bits", c.length_bits);
  w.Put("byte_order", c.byte_order);
  w.Put("signed", c.is_signed);
  w.Put("scale", c.scale);
  w.Put("offset", c.offset);
  w.Put("dlc", c.dlc);
  w.EndMap();
}

void Emit(ConfigWriter& w, const drivers::CanConfig& c) {
  w.BeginMap("can");
  w.Put("enabled", c.enabled);
  w.Put("interface", c.interface);
  w.Put("mode", c.mode);
  w.Put("wheel_speed_unit", c.wheel_speed_unit);
  w.Put("wheel_radius_m", c.wheel_radius_m);
  w.Put("track_width_m", c.track_width_m);
  w.Put("max_pair_skew_s", c.max_pair_skew_s);
  w.BeginList("signals", c.signals.empty());
  for (const drivers::CanSignalConfig& s : c.signals) Emit(w, s);
  w.EndList();
  w.EndMap();
}

void Emit(ConfigWriter& w, const char* key, const estimator::ExtrinsicConfig& c) {
  w.BeginMap(key);
  w.Put("translation_m", c.translation_m);
  w.Put("rotation_rpy_deg", c.rotation_rpy_deg);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::ImuNoiseConfig& c) {
  w.BeginMap("imu_noise");
  w.Put("acc_noise_density_mps2_per_sqrthz", c.acc_noise_density_mps2_per_sqrthz);
  w.Put("gyro_noise_density_radps_per_sqrthz", c.gyro_noise_density_radps_per_sqrthz);
  w.Put("acc_bias_random_walk_mps3_per_sqrthz", c.acc_bias_random_walk_mps3_per_sqrthz);
  w.Put("gyro_bias_random_walk_radps2_per_sqrthz", c.gyro_bias_random_walk_radps2_per_sqrthz);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::DivergenceConfig& c) {
  w.BeginMap("divergence");
  w.Put("enabled", c.enabled);
  w.Put("max_speed_mps", c.max_speed_mps);
  w.Put("max_bias_acc_mps2", c.max_bias_acc_mps2);
  w.Put("max_bias_gyro_radps", c.max_bias_gyro_radps);
  w.Put("max_failed_sweeps", c.max_failed_sweeps);
  w.Put("max_prediction_error_m", c.max_prediction_error_m);
  w.Put("max_prediction_error_rad", c.max_prediction_error_rad);
  w.Put("max_inconsistent_sweeps", c.max_inconsistent_sweeps);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::DynamicInitializer::Options& c) {
  w.BeginMap("initializer");
  w.Put("min_frames", c.min_frames);
  w.Put("position_sigma_m", c.position_sigma_m);
  w.Put("rotation_sigma_rad", c.rotation_sigma_rad);
  w.Put("acc_bias_prior_sigma_mps2", c.acc_bias_prior_sigma_mps2);
  w.Put("max_acc_bias_std_mps2", c.max_acc_bias_std_mps2);
  w.Put("require_acc_bias", c.require_acc_bias);
  w.Put("max_normalized_rms", c.max_normalized_rms);
  w.Put("max_gravity_norm_error_mps2", c.max_gravity_norm_error_mps2);
  w.Put("max_gyro_bias_radps", c.max_gyro_bias_radps);
  w.Put("max_gravity_tilt_std_rad", c.max_gravity_tilt_std_rad);
  w.Put("max_velocity_std_mps", c.max_velocity_std_mps);
  w.Put("gyro_iterations", c.gyro_iterations);
  w.Put("gravity_iterations", c.gravity_iterations);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::DynamicBootstrapConfig& c) {
  w.BeginMap("bootstrap");
  w.Put("window_frames", c.window_frames);
  w.Put("imu_buffer_s", c.imu_buffer_s);
  w.Put("max_imu_lag_s", c.max_imu_lag_s);
  w.Put("max_sweep_gap_s", c.max_sweep_gap_s);
  w.Put("max_speed_mps", c.max_speed_mps);
  w.Put("refine_deskew_m", c.refine_deskew_m);
  w.Put("deskew_refinements", c.deskew_refinements);
  w.Put("line_min_ratio", c.line_min_ratio);
  Emit(w, c.initializer);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::WheelFactorConfig& c) {
  w.BeginMap("wheel");
  w.Put("enabled", c.enabled);
  Emit(w, "T_imu_base", c.T_imu_base);
  w.Put("sigma_forward_mps", c.sigma_forward_mps);
  w.Put("sigma_lateral_mps", c.sigma_lateral_mps);
  w.Put("sigma_vertical_mps", c.sigma_vertical_mps);
  w.Put("max_gap_s", c.max_gap_s);
  w.Put("max_innovation_mps", c.max_innovation_mps);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::StandstillConfig& c) {
  w.BeginMap("standstill");
  w.Put("enabled", c.enabled);
  w.Put("imu_window_s", c.imu_window_s);
  w.Put("max_acc_std_mps2", c.max_acc_std_mps2);
  w.Put("max_gyro_std_radps", c.max_gyro_std_radps);
  w.Put("max_specific_force_error_mps2", c.max_specific_force_error_mps2);
  w.Put("max_rate_radps", c.max_rate_radps);
  w.Put("max_lidar_speed_mps", c.max_lidar_speed_mps);
  w.Put("sigma_velocity_mps", c.sigma_velocity_mps);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::ImuNoiseAdapterConfig& c) {
  w.BeginMap("imu_noise_adapter");
  w.Put("enabled", c.enabled);
  w.Put("gain", c.gain);
  w.Put("time_constant_s", c.time_constant_s);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::TimeOffsetConfig& c) {
  w.BeginMap("time_offset");
  w.Put("enabled", c.enabled);
  w.Put("estimate", c.estimate);
  w.Put("initial_offset_s", c.initial_offset_s);
  w.Put("max_offset_s", c.max_offset_s);
  w.Put("span_s", c.span_s);
  w.Put("history_s", c.history_s);
  w.Put("gate_sigma_s", c.gate_sigma_s);
  w.Put("coarse_gate_sigma_s", c.coarse_gate_sigma_s);
  w.Put("min_rows", c.min_rows);
  w.Put("max_step_s", c.max_step_s);
  w.Put("huber_rad", c.huber_rad);
  w.Put("tilt_weight", c.tilt_weight);
  w.Put("operating_point_tolerance_s", c.operating_point_tolerance_s);
  w.Put("initial_sigma_s", c.initial_sigma_s);
  w.Put("window_prior_sigma_s", c.window_prior_sigma_s);
  w.Put("window_follows_estimate", c.window_follows_estimate);
  w.Put("correlated_rows", c.correlated_rows);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::VisibilityConfig& c) {
  w.BeginMap("visibility");
  w.Put("enabled", c.enabled);
  w.Put("rings", c.rings);
  w.Put("columns", c.columns);
  w.Put("min_range_m", c.min_range_m);
  w.Put("max_range_m", c.max_range_m);
  w.Put("beam_tolerance_m", c.beam_tolerance_m);
  w.Put("margin_m", c.margin_m);
  w.Put("margin_ratio", c.margin_ratio);
  w.Put("neighbour_columns", c.neighbour_columns);
  w.Put("votes_to_remove", c.votes_to_remove);
  w.Put("check_radius_m", c.check_radius_m);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::MapVisibilityConfig& c) {
  w.BeginMap("visibility");
  w.Put("enabled", c.enabled);
  w.Put("votes_to_remove", c.votes_to_remove);
  w.Put("check_radius_m", c.check_radius_m);
  w.Put("recent_nodes", c.recent_nodes);
  w.EndMap();
}

/// The window's scalar options, in the shipped file's order.
void EmitWindowOptions(ConfigWriter& w, const estimator::WindowEstimatorConfig& c) {
  w.Put("window_size", c.window_size);
  w.Put("max_iterations", c.max_iterations);
  w.Put("prealign", c.prealign);
  w.Put("reassociations", c.reassociations);
  w.Put("edge_threshold_m2", c.edge_threshold_m2);
  w.Put("max_edges_per_sector", c.max_edges_per_sector);
  w.Put("local_map_radius_m", c.local_map_radius_m);
  w.Put("lidar_sigma_m", c.lidar_sigma_m);
  w.Put("huber_m", c.huber_m);
  w.Put("degenerate_eigenvalue", c.degenerate_eigenvalue);
  w.Put("lidar_floor_sigma_m", c.lidar_floor_sigma_m);
  w.Put("lidar_floor_sigma_tilt_rad", c.lidar_floor_sigma_tilt_rad);
  w.Put("lidar_floor_sigma_yaw_rad", c.lidar_floor_sigma_yaw_rad);
  w.Put("estimate_extrinsic", c.estimate_extrinsic);
  w.Put("extrinsic_prior_sigma_m", c.extrinsic_prior_sigma_m);
  w.Put("extrinsic_prior_sigma_rad", c.extrinsic_prior_sigma_rad);
  w.Put("calibrate_extrinsic_s", c.calibrate_extrinsic_s);
  w.Put("calibrate_retry_s", c.calibrate_retry_s);
  w.Put("init_sigma_position_m", c.init_sigma_position_m);
  w.Put("init_sigma_rotation_rad", c.init_sigma_rotation_rad);
  w.Put("init_sigma_velocity_mps", c.init_sigma_velocity_mps);
  w.Put("init_sigma_bias_acc_mps2", c.init_sigma_bias_acc_mps2);
  w.Put("init_sigma_bias_gyro_radps", c.init_sigma_bias_gyro_radps);
  w.Put("bias_prior_sigma_acc_mps2", c.bias_prior_sigma_acc_mps2);
  w.Put("bias_prior_sigma_gyro_radps", c.bias_prior_sigma_gyro_radps);
  w.Put("dynamic_init", c.dynamic_init);
  w.Put("static_max_speed_mps", c.static_max_speed_mps);
  w.Put("covariance", c.covariance);
  w.Put("init_tilt_follows_bias", c.init_tilt_follows_bias);
  w.Put("estimate_gravity_tilt", c.estimate_gravity_tilt);
}

/// `odometry` is not a key (the loader's rule).
void Emit(ConfigWriter& w, const estimator::WindowEstimatorConfig& c) {
  w.BeginMap("window");
  EmitWindowOptions(w, c);
  Emit(w, c.divergence);
  Emit(w, c.bootstrap);
  Emit(w, c.wheel);
  Emit(w, c.standstill);
  Emit(w, c.imu_noise_adapter);
  Emit(w, c.time_offset);
  Emit(w, c.visibility);
  w.EndMap();
}

void Emit(ConfigWriter& w, const estimator::ScanContextConfig& c) {
  w.BeginMap("descriptor");
  w.Put("rings", c.rings);
  w.Put("sectors", c.sectors);
  w.Put("max_range_m", c.max_range_m);
  w.Put("min_range_m", c.min_range_m);
  w.Put("height_offset_m", c.height_offset_m);
  w.Put("candidates", c.candidates);
  w.Put("max_distance", c.max_distance);
  w.EndMap();
}

/// The origin's three keys are absent by default (NaN: the first accepted fix); each is
/// written only when set.
void Emit(ConfigWriter& w, const estimator::GnssConfig& c) {
  w.BeginMap("gnss");
  w.Put("enabled", c.enabled);
  if (!c.has_origin())
    w.Comment("origin_lat_deg, _lon_deg, _height_m absent: the first accepted fix");
  const std::array<std::pair<const char*, double>, 3> origin = {{
      {"origin_lat_deg", c.origin_lat_deg},
      {"origin_lon_deg", c.origin_lon_deg},
      {"origin_height_m", c.origin_height_m},
  }};
  for (const auto& [key, value] : origin) {
    if (!std::isnan(value)) w.Put(key, value);
  }
  w.Put("antenna_imu_m",
        std::array<double, 3>{c.antenna_imu_m.x(), c.antenna_imu_m.y(), c.antenna_imu_m.z()});
  w.Put("min_fix_type", c.min_fix_type);
  w.Put("max_h_acc_m", c.max_h_acc_m);
  w.Put("sigma_scale", c.sigma_scale);
  w.Put("min_sigma_m", c.min_sigma_m);
  w.Put("min_interval_s", c.min_interval_s);
  w.Put("correlation_time_s", c.correlation_time_s);
  w.Put("max_interpolation_s", c.max_interpolation_s);
  w.Put("align_min_distance_m", c.align_min_distance_m);
  w.Put("optimize_every_fixes", c.optimize_every_fixes);
  w.Put("gate_sigmas", c.gate_sigmas);
  w.Put("gate_reset_after", c.gate_reset_after);
  w.Put("kernel", c.kernel);
  w.Put("max_chi2", c.max_chi2);
  w.EndMap();
}

/// The matchers' own settings (coarse, fine) are not keys.
void Emit(ConfigWriter& w, const estimator::LoopClosureConfig& c) {
  w.BeginMap("loop_closure");
  w.Put("enabled", c.enabled);
  w.Put("descriptor_candidates", c.descriptor_candidates);
  w.Put("max_drift_ratio", c.max_drift_ratio);
  Emit(w, c.visibility);
  Emit(w, c.descriptor);
  w.Put("keyframe_distance_m", c.keyframe_distance_m);
  w.Put("keyframe_angle_rad", c.keyframe_angle_rad);
  w.Put("search_radius_m", c.search_radius_m);
  w.Put("min_separation_s", c.min_separation_s);
  w.Put("place_radius_m", c.place_radius_m);
  w.Put("place_angle_rad", c.place_angle_rad);
  w.Put("attempt_every_nodes", c.attempt_every_nodes);
  w.Put("submap_half_width", c.submap_half_width);
  w.Put("inlier_distance_m", c.inlier_distance_m);
  w.Put("min_fitness", c.min_fitness);
  w.Put("min_inliers", c.min_inliers);
  w.Put("min_hessian_eigenvalue", c.min_hessian_eigenvalue);
  w.Put("max_correction_m", c.max_correction_m);
  w.Put("max_correction_rad", c.max_correction_rad);
  w.Put("odometry_sigma_m", c.odometry_sigma_m);
  w.Put("odometry_sigma_rad", c.odometry_sigma_rad);
  w.Put("loop_sigma_m", c.loop_sigma_m);
  w.Put("loop_sigma_rad", c.loop_sigma_rad);
  w.Put("max_loop_chi2", c.max_loop_chi2);
  w.Put("loop_kernel", c.loop_kernel);
  w.Put("max_iterations", c.max_iterations);
  w.Put("output_max_rate_mps", c.output_max_rate_mps);
  w.Put("output_max_rate_radps", c.output_max_rate_radps);
  Emit(w, c.gnss);
  w.EndMap();
}

/// `registration` is not a key (the daemon uses estimator.loop_closure's).
void Emit(ConfigWriter& w, const estimator::LocalizationConfig& c) {
  w.BeginMap("localization");
  w.Put("relocalize_max_descriptor_distance", c.relocalize_max_descriptor_distance);
  w.Put("relocalize_candidates", c.relocalize_candidates);
  w.Put("relocalize_min_margin", c.relocalize_min_margin);
  w.Put("distinct_m", c.distinct_m);
  w.Put("relocalize_max_correction_m", c.relocalize_max_correction_m);
  w.Put("relocalize_max_correction_rad", c.relocalize_max_correction_rad);
  w.Put("relocalize_every_m", c.relocalize_every_m);
  w.Put("relocalize_every_rad", c.relocalize_every_rad);
  w.Put("confirmations", c.confirmations);
  w.Put("track_every_m", c.track_every_m);
  w.Put("track_every_rad", c.track_every_rad);
  w.Put("submap_radius_m", c.submap_radius_m);
  w.Put("submap_max_nodes", c.submap_max_nodes);
  w.Put("track_min_fitness", c.track_min_fitness);
  w.Put("track_max_correction_m", c.track_max_correction_m);
  w.Put("track_max_correction_rad", c.track_max_correction_rad);
  w.Put("lost_after_failures", c.lost_after_failures);
  w.EndMap();
}

void EmitEstimator(ConfigWriter& w, const DaemonConfig& c) {
  const estimator::EstimatorConfig& e = c.estimator;
  w.BeginMap("estimator");
  w.Put("mode", e.mode);
  Emit(w, e.imu_noise);
  Emit(w, "extrinsic_imu_lidar", e.extrinsic_imu_lidar);
  w.Put("gravity_mps2", e.gravity_mps2);
  w.Put("init_static_duration_s", e.init_static_duration_s);
  w.Put("plane_voxel_m", e.plane_voxel_m);
  w.Put("edge_voxel_m", e.edge_voxel_m);
  w.Put("local_map_radius_m", e.local_map_radius_m);
  w.Put("output_rebase_rate_mps", e.output_rebase_rate_mps);
  w.Put("output_rebase_rate_radps", e.output_rebase_rate_radps);
  Emit(w, c.window);
  Emit(w, c.loop_closure);
  Emit(w, c.localization);
  w.EndMap();
}

void Emit(ConfigWriter& w, const MapFilesConfig& c) {
  w.BeginMap("map");
  w.Put("save_path", c.save_path);
  w.Put("load_path", c.load_path);
  w.Put("localize", c.localize);
  w.EndMap();
}

void Emit(ConfigWriter& w, const StateConfig& c) {
  w.BeginMap("state");
  w.Put("time_offset_file", c.time_offset_file);
  w.Put("save_period_s", c.save_period_s);
  w.EndMap();
}

void Emit(ConfigWriter& w, const ipc::IpcConfig& c) {
  w.BeginMap("ipc");
  w.Put("domain_id", c.domain_id);
  w.Put("dds_config_file", c.dds_config_file);
  w.Put("require_loopback", c.require_loopback);
  w.Put("pose_topic", c.pose_topic);
  w.Put("odometry_topic", c.odometry_topic);
  w.Put("health_topic", c.health_topic);
  w.Put("path_topic", c.path_topic);
  w.Put("path_max_poses", c.path_max_poses);
  w.Put("map_topic", c.map_topic);
  w.Put("map_max_points", c.map_max_points);
  w.Put("map_publish_period_s", c.map_publish_period_s);
  w.Put("stamp_clock", c.stamp_clock);
  w.Put("odom_odometry_topic", c.odom_odometry_topic);
  w.Put("initialpose_topic", c.initialpose_topic);
  w.Put("sweep_topic", c.sweep_topic);
  w.Put("tf_topic", c.tf_topic);
  w.Put("tf_static_topic", c.tf_static_topic);
  w.Put("map_odom_period_s", c.map_odom_period_s);
  w.BeginMap("frames");
  w.Put("map", c.frames.map);
  w.Put("odom", c.frames.odom);
  w.Put("base_link", c.frames.base_link);
  w.Put("imu", c.frames.imu);
  w.Put("lidar", c.frames.lidar);
  w.EndMap();
  w.EndMap();
}

void Emit(ConfigWriter& w, const LoggingConfig& c) {
  w.BeginMap("logging");
  w.Put("directory", c.directory);
  w.Put("file_name", c.file_name);
  w.Put("file_level", c.file_level);
  w.Put("stderr_level", c.stderr_level);
  w.Put("journald", c.journald);
  w.Put("max_file_size_mb", c.max_file_size_mb);
  w.Put("max_files", c.max_files);
  w.Put("status_period_s", c.status_period_s);
  w.EndMap();
}

void Emit(ConfigWriter& w, const RecordConfig& c) {
  w.BeginMap("record");
  w.Put("ring", c.ring);
  w.Put("directory", c.directory);
  w.Put("ring_minutes", c.ring_minutes);
  w.Put("segment_s", c.segment_s);
  w.Put("max_disk_mb", c.max_disk_mb);
  w.Put("incident_before_s", c.incident_before_s);
  w.Put("incident_after_s", c.incident_after_s);
  w.Put("incidents_max_count", c.incidents_max_count);
  w.Put("incidents_max_mb", c.incidents_max_mb);
  w.EndMap();
}

void Emit(ConfigWriter& w, const RealtimeConfig& c) {
  w.BeginMap("realtime");
  w.Put("enabled", c.enabled);
  w.Put("lock_memory", c.lock_memory);
  w.Put("max_sweep_lag_s", c.max_sweep_lag_s);
  w.BeginList("threads", c.threads.empty());
  for (const ThreadSchedConfig& t : c.threads) {
    w.BeginMap(nullptr, /*flow=*/true);
    w.Put("name", t.name);
    w.Put("priority", t.priority);
    w.Put("cpu", t.cpu);
    w.Put("nice", t.nice);
    w.EndMap();
  }
  w.EndList();
  w.EndMap();
}

void Emit(ConfigWriter& w, const ControlConfig& c) {
  w.BeginMap("control");
  w.Put("socket", c.socket);
  w.Put("group", c.group);
  w.Put("request_timeout_s", c.request_timeout_s);
  w.Put("command_timeout_s", c.command_timeout_s);
  w.Put("max_clients", c.max_clients);
  w.EndMap();
}

}  // namespace

std::string PrintConfig(const DaemonConfig& config) {
  ConfigWriter w;
  w.Comment(
      "swliod --print-config: the effective configuration, every key with its value (defaults "
      "filled in,\nrelative paths resolved). What each key means: config/swlio.yaml.");
  w.BeginMap(nullptr);
  w.Put("config_version", config.config_version);
  Emit(w, config.lidar);
  Emit(w, config.imu);
  Emit(w, config.can);
  EmitEstimator(w, config);
  Emit(w, config.map);
  Emit(w, config.state);
  Emit(w, config.ipc);
  Emit(w, config.logging);
  Emit(w, config.record);
  Emit(w, config.realtime);
  Emit(w, config.control);
  w.EndMap();
  return w.Text();
}

}  // namespace swlio::daemon
