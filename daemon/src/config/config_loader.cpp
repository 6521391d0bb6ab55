// The only file that reads YAML (config_printer.cpp, the other yaml-cpp user, only writes it
// for --print-config). A `Section` walks one YAML mapping: each Get() call takes a known key,
// checks its type and stores it; Removed() refuses a key the schema dropped, saying what
// replaced it; Finish() reports every key nobody took.
// Marks (line/column) of every key are remembered so that the modules' Validate() results,
// which only know key names, can be reported with their place in the file.

#include "swlio/daemon/config/config_loader.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <utility>

namespace swlio::daemon {
namespace {

struct Context {
  std::string file;
  std::vector<ConfigError> errors;
  std::map<std::string, YAML::Mark> marks;  ///< dotted key → where its value starts

  void Error(const YAML::Mark& mark, const std::string& key, const std::string& reason) {
    const bool known = mark.line >= 0;
    errors.push_back({file, known ? mark.line + 1 : 0, known ? mark.column + 1 : 0, key, reason});
  }
};

std::string Describe(const YAML::Node& node) {
  if (node.IsNull()) return "nothing";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a mapping";
  return "'" + node.Scalar() + "'";
}

/// Edit distance, for "did you mean" hints on unknown keys.
size_t Levenshtein(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// Decimal, or hexadecimal with a 0x prefix (CAN identifiers are written in hex).
bool ParseInt(const std::string& text, int64_t* out) {
  const bool hex = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
  const char* begin = text.data() + (hex ? 2 : 0);
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(begin, end, *out, hex ? 16 : 10);
  return ec == std::errc() && ptr == end && !(hex && *begin == '-');
}

bool ParseDouble(const std::string& text, double* out) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, *out);
  return ec == std::errc() && ptr == end && std::isfinite(*out);
}

bool ParseBool(const std::string& text, bool* out) {
  static const std::set<std::string> kTrue = {"true", "True", "TRUE", "yes", "Yes", "on", "On"};
  static const std::set<std::string> kFalse = {"false", "False", "FALSE", "no", "No", "off", "Off"};
  if (kTrue.count(text) != 0) {
    *out = true;
    return true;
  }
  if (kFalse.count(text) != 0) {
    *out = false;
    return true;
  }
  return false;
}

class Section {
 public:
  Section(const YAML::Node& node, std::string path, Context* ctx)
      : node_(node), path_(std::move(path)), ctx_(ctx) {}

  void Get(const char* key, bool& out) {
    ParseScalar(key, "true or false", [&](const std::string& s) { return ParseBool(s, &out); });
  }
  void Get(const char* key, double& out) {
    ParseScalar(key, "a number", [&](const std::string& s) { return ParseDouble(s, &out); });
  }
  void Get(const char* key, std::string& out) {
    ParseScalar(key, "a string", [&](const std::string& s) {
      out = s;
      return true;
    });
  }
  void Get(const char* key, int64_t& out) { GetInteger(key, out); }
  void Get(const char* key, uint16_t& out) { GetInteger(key, out); }
  void Get(const char* key, int& out) { GetInteger(key, out); }
  void Get(const char* key, size_t& out) { GetInteger(key, out); }

  template <size_t N>
  void Get(const char* key, std::array<double, N>& out) {
    const YAML::Node value = Take(key);
    if (!value) return;
    std::array<double, N> parsed{};
    bool ok = value.IsSequence() && value.size() == N;
    for (size_t i = 0; ok && i < N; ++i) {
      ok = value[i].IsScalar() && ParseDouble(value[i].Scalar(), &parsed[i]);
    }
    if (!ok) {
      ctx_->Error(value.Mark(), Path(key),
                  "expected a list of " + std::to_string(N) + " numbers, got " + Describe(value));
      return;
    }
    out = parsed;
  }

  /// A nested mapping; absent → an empty section (all defaults).
  Section Child(const char* key) {
    const YAML::Node value = Take(key);
    if (value && !value.IsMap()) {
      ctx_->Error(value.Mark(), Path(key), "expected a mapping of keys, got " + Describe(value));
      return Section(YAML::Node(), Path(key), ctx_);
    }
    return Section(value ? value : YAML::Node(), Path(key), ctx_);
  }

  /// A list of mappings: calls `each(Section)` for every item, whose path is "key[i]";
  /// absent → no call. Items that are not mappings are reported.
  template <typename Each>
  /// Calls `each` for every item of the list at `key`; false when the key is absent.
  bool ForEachChild(const char* key, Each each) {
    const YAML::Node value = Take(key);
    if (!value) return false;
    if (!value.IsSequence()) {
      ctx_->Error(value.Mark(), Path(key), "expected a list of mappings, got " + Describe(value));
      return true;
    }
    for (size_t i = 0; i < value.size(); ++i) {
      const std::string item_path = Path(key) + "[" + std::to_string(i) + "]";
      const YAML::Node item = value[i];
      if (!item.IsMap()) {
        ctx_->Error(item.Mark(), item_path, "expected a mapping of keys, got " + Describe(item));
        continue;
      }
      ctx_->marks[item_path] = item.Mark();
      each(Section(item, item_path, ctx_));
    }
    return true;
  }

  /// A key removed from the schema because nothing read it: when present, an error that says
  /// what to use `instead`. Removed keys are not offered as "did you mean" hints.
  void Removed(const char* key, const std::string& instead) {
    removed_.emplace_back(key);
    const auto [k, value] = Find(key);
    if (!k) return;
    ctx_->marks[Path(key)] = k.Mark();
    ctx_->Error(k.Mark(), Path(key), "removed key (it was never read); " + instead);
  }

  /// Reports keys that no Get()/Child()/Removed() took, and duplicated keys.
  void Finish() {
    if (!node_.IsMap()) return;
    std::set<std::string> seen;
    for (const auto& entry : node_) {
      const YAML::Node& k = entry.first;
      const std::string name = k.IsScalar() ? k.Scalar() : Describe(k);
      if (!seen.insert(name).second) {
        ctx_->Error(k.Mark(), Path(name.c_str()), "duplicate key");
      } else if (std::find(known_.begin(), known_.end(), name) == known_.end() &&
                 std::find(removed_.begin(), removed_.end(), name) == removed_.end()) {
        ctx_->Error(k.Mark(), Path(name.c_str()), "unknown key" + Suggestion(name));
      }
    }
  }

  const std::string& path() const { return path_; }

 private:
  std::string Path(const char* key) const { return path_.empty() ? key : path_ + "." + key; }

  /// The key node and the value of `key` in this mapping; undefined handles when absent.
  std::pair<YAML::Node, YAML::Node> Find(const char* key) const {
    if (node_.IsMap()) {
      for (const auto& entry : node_) {
        if (entry.first.IsScalar() && entry.first.Scalar() == key) {
          return {entry.first, entry.second};
        }
      }
    }
    return {YAML::Node(YAML::NodeType::Undefined), YAML::Node(YAML::NodeType::Undefined)};
  }

  /// The value under `key` (or an undefined handle), remembering that the key is known.
  YAML::Node Take(const char* key) {
    known_.emplace_back(key);
    const auto [k, value] = Find(key);
    if (k) ctx_->marks[Path(key)] = k.Mark();
    return value;
  }

  template <typename Parse>
  void ParseScalar(const char* key, const char* expected, Parse parse) {
    const YAML::Node value = Take(key);
    if (!value) return;
    if (!value.IsScalar() || !parse(value.Scalar())) {
      ctx_->Error(value.Mark(), Path(key),
                  std::string("expected ") + expected + ", got " + Describe(value));
    }
  }

  template <typename Int>
  void GetInteger(const char* key, Int& out) {
    const YAML::Node value = Take(key);
    if (!value) return;
    int64_t v = 0;
    constexpr auto kMin = static_cast<int64_t>(std::numeric_limits<Int>::min());
    constexpr auto kMax = static_cast<int64_t>(
        std::min<uint64_t>(std::numeric_limits<Int>::max(), std::numeric_limits<int64_t>::max()));
    if (!value.IsScalar() || !ParseInt(value.Scalar(), &v) || v < kMin || v > kMax) {
      ctx_->Error(value.Mark(), Path(key),
                  "expected an integer in [" + std::to_string(kMin) + ", " + std::to_string(kMax) +
                      "], got " + Describe(value));
      return;
    }
    out = static_cast<Int>(v);
  }

  std::string Suggestion(const std::string& name) const {
    std::string best;
    size_t best_distance = 4;  // only close matches are worth suggesting
    for (const auto& k : known_) {
      const size_t d = Levenshtein(name, k);
      if (d < best_distance) {
        best_distance = d;
        best = k;
      }
    }
    return best.empty() ? "" : " (did you mean '" + best + "'?)";
  }

  YAML::Node node_;
  std::string path_;
  Context* ctx_;
  std::vector<std::string> known_;
  std::vector<std::string> removed_;
};

void Bind(Section s, drivers::LidarConfig& c) {
  s.Get("model", c.model);
  s.Get("bind_address", c.bind_address);
  s.Get("msop_port", c.msop_port);
  s.Get("difop_port", c.difop_port);
  s.Get("cut_angle_deg", c.cut_angle_deg);
  s.Get("min_range_m", c.min_range_m);
  s.Get("max_range_m", c.max_range_m);
  s.Get("rcvbuf_bytes", c.rcvbuf_bytes);
  s.Get("rx_batch_ms", c.rx_batch_ms);
  s.Get("vertical_angles_deg", c.vertical_angles_deg);
  s.Get("rpm", c.rpm);
  s.Get("lens_offset_m", c.lens_offset_m);  // absent: NaN, the model's vendor value
  s.Finish();
}

void Bind(Section s, drivers::ImuConfig& c) {
  s.Get("device", c.device);
  s.Get("baud", c.baud);
  s.Get("output_rate_hz", c.output_rate_hz);
  s.Get("configure_on_start", c.configure_on_start);
  s.Get("reply_timeout_ms", c.reply_timeout_ms);
  s.Get("configure_retries", c.configure_retries);
  s.Finish();
}

void Bind(Section s, drivers::CanSignalConfig& c) {
  s.Get("role", c.role);
  s.Get("can_id", c.can_id);
  s.Get("extended", c.extended);
  s.Get("start_bit", c.start_bit);
  s.Get("byte_offset", c.byte_offset);
  s.Get("length_bits", c.length_bits);
  s.Get("byte_order", c.byte_order);
  s.Get("signed", c.is_signed);
  s.Get("scale", c.scale);
  s.Get("offset", c.offset);
  s.Get("dlc", c.dlc);
  s.Finish();
}

void Bind(Section s, drivers::CanConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("interface", c.interface);
  s.Get("mode", c.mode);
  s.Get("wheel_speed_unit", c.wheel_speed_unit);
  s.Get("wheel_radius_m", c.wheel_radius_m);
  s.Get("track_width_m", c.track_width_m);
  s.Get("max_pair_skew_s", c.max_pair_skew_s);
  s.ForEachChild("signals", [&](const Section& item) { Bind(item, c.signals.emplace_back()); });
  s.Finish();
}

void Bind(Section s, estimator::ImuNoiseConfig& c) {
  s.Get("acc_noise_density_mps2_per_sqrthz", c.acc_noise_density_mps2_per_sqrthz);
  s.Get("gyro_noise_density_radps_per_sqrthz", c.gyro_noise_density_radps_per_sqrthz);
  s.Get("acc_bias_random_walk_mps3_per_sqrthz", c.acc_bias_random_walk_mps3_per_sqrthz);
  s.Get("gyro_bias_random_walk_radps2_per_sqrthz", c.gyro_bias_random_walk_radps2_per_sqrthz);
  s.Finish();
}

void Bind(Section s, estimator::ExtrinsicConfig& c) {
  s.Get("translation_m", c.translation_m);
  s.Get("rotation_rpy_deg", c.rotation_rpy_deg);
  s.Finish();
}

void Bind(Section s, estimator::DynamicInitializer::Options& c) {
  s.Get("min_frames", c.min_frames);
  s.Get("position_sigma_m", c.position_sigma_m);
  s.Get("rotation_sigma_rad", c.rotation_sigma_rad);
  s.Get("acc_bias_prior_sigma_mps2", c.acc_bias_prior_sigma_mps2);
  s.Get("max_acc_bias_std_mps2", c.max_acc_bias_std_mps2);
  s.Get("require_acc_bias", c.require_acc_bias);
  s.Get("max_normalized_rms", c.max_normalized_rms);
  s.Get("max_gravity_norm_error_mps2", c.max_gravity_norm_error_mps2);
  s.Get("max_gyro_bias_radps", c.max_gyro_bias_radps);
  s.Get("max_gravity_tilt_std_rad", c.max_gravity_tilt_std_rad);
  s.Get("max_velocity_std_mps", c.max_velocity_std_mps);
  s.Get("gyro_iterations", c.gyro_iterations);
  s.Get("gravity_iterations", c.gravity_iterations);
  s.Finish();
}

void Bind(Section s, estimator::DivergenceConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("max_speed_mps", c.max_speed_mps);
  s.Get("max_bias_acc_mps2", c.max_bias_acc_mps2);
  s.Get("max_bias_gyro_radps", c.max_bias_gyro_radps);
  s.Get("max_failed_sweeps", c.max_failed_sweeps);
  s.Get("max_prediction_error_m", c.max_prediction_error_m);
  s.Get("max_prediction_error_rad", c.max_prediction_error_rad);
  s.Get("max_inconsistent_sweeps", c.max_inconsistent_sweeps);
  s.Finish();
}

/// `odometry` is not a key: the estimator takes it from the window's.
void Bind(Section s, estimator::DynamicBootstrapConfig& c) {
  Bind(s.Child("initializer"), c.initializer);
  s.Get("window_frames", c.window_frames);
  s.Get("imu_buffer_s", c.imu_buffer_s);
  s.Get("max_imu_lag_s", c.max_imu_lag_s);
  s.Get("max_sweep_gap_s", c.max_sweep_gap_s);
  s.Get("max_speed_mps", c.max_speed_mps);
  s.Get("refine_deskew_m", c.refine_deskew_m);
  s.Get("deskew_refinements", c.deskew_refinements);
  s.Get("line_min_ratio", c.line_min_ratio);
  s.Finish();
}

void Bind(Section s, estimator::ImuNoiseAdapterConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("gain", c.gain);
  s.Get("time_constant_s", c.time_constant_s);
  s.Finish();
}

void Bind(Section s, estimator::TimeOffsetConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("estimate", c.estimate);
  s.Get("initial_offset_s", c.initial_offset_s);
  s.Get("max_offset_s", c.max_offset_s);
  s.Get("span_s", c.span_s);
  s.Get("history_s", c.history_s);
  s.Get("gate_sigma_s", c.gate_sigma_s);
  s.Get("coarse_gate_sigma_s", c.coarse_gate_sigma_s);
  s.Get("min_rows", c.min_rows);
  s.Get("max_step_s", c.max_step_s);
  s.Get("huber_rad", c.huber_rad);
  s.Get("tilt_weight", c.tilt_weight);
  s.Get("operating_point_tolerance_s", c.operating_point_tolerance_s);
  s.Get("initial_sigma_s", c.initial_sigma_s);
  s.Get("window_prior_sigma_s", c.window_prior_sigma_s);
  s.Get("window_follows_estimate", c.window_follows_estimate);
  s.Get("correlated_rows", c.correlated_rows);
  s.Finish();
}

void Bind(Section s, estimator::VisibilityConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("rings", c.rings);
  s.Get("columns", c.columns);
  s.Get("min_range_m", c.min_range_m);
  s.Get("max_range_m", c.max_range_m);
  s.Get("beam_tolerance_m", c.beam_tolerance_m);
  s.Get("margin_m", c.margin_m);
  s.Get("margin_ratio", c.margin_ratio);
  s.Get("neighbour_columns", c.neighbour_columns);
  s.Get("votes_to_remove", c.votes_to_remove);
  s.Get("check_radius_m", c.check_radius_m);
  s.Finish();
}

void Bind(Section s, estimator::MapVisibilityConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("votes_to_remove", c.votes_to_remove);
  s.Get("check_radius_m", c.check_radius_m);
  s.Get("recent_nodes", c.recent_nodes);
  s.Finish();
}

void Bind(Section s, estimator::StandstillConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("imu_window_s", c.imu_window_s);
  s.Get("max_acc_std_mps2", c.max_acc_std_mps2);
  s.Get("max_gyro_std_radps", c.max_gyro_std_radps);
  s.Get("max_specific_force_error_mps2", c.max_specific_force_error_mps2);
  s.Get("max_rate_radps", c.max_rate_radps);
  s.Get("max_lidar_speed_mps", c.max_lidar_speed_mps);
  s.Get("sigma_velocity_mps", c.sigma_velocity_mps);
  s.Finish();
}

/// `T_imu_base` as translation_m and rotation_rpy_deg (the extrinsic's convention).
void Bind(Section s, estimator::WheelFactorConfig& c) {
  s.Get("enabled", c.enabled);
  Bind(s.Child("T_imu_base"), c.T_imu_base);
  s.Get("sigma_forward_mps", c.sigma_forward_mps);
  s.Get("sigma_lateral_mps", c.sigma_lateral_mps);
  s.Get("sigma_vertical_mps", c.sigma_vertical_mps);
  s.Get("max_gap_s", c.max_gap_s);
  s.Get("max_innovation_mps", c.max_innovation_mps);
  s.Finish();
}

void Bind(Section s, estimator::GnssConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("origin_lat_deg", c.origin_lat_deg);
  s.Get("origin_lon_deg", c.origin_lon_deg);
  s.Get("origin_height_m", c.origin_height_m);
  std::array<double, 3> antenna = {c.antenna_imu_m.x(), c.antenna_imu_m.y(), c.antenna_imu_m.z()};
  s.Get("antenna_imu_m", antenna);
  c.antenna_imu_m = Eigen::Vector3d(antenna[0], antenna[1], antenna[2]);
  s.Get("min_fix_type", c.min_fix_type);
  s.Get("max_h_acc_m", c.max_h_acc_m);
  s.Get("sigma_scale", c.sigma_scale);
  s.Get("min_sigma_m", c.min_sigma_m);
  s.Get("min_interval_s", c.min_interval_s);
  s.Get("correlation_time_s", c.correlation_time_s);
  s.Get("max_interpolation_s", c.max_interpolation_s);
  s.Get("align_min_distance_m", c.align_min_distance_m);
  s.Get("optimize_every_fixes", c.optimize_every_fixes);
  s.Get("gate_sigmas", c.gate_sigmas);
  s.Get("gate_reset_after", c.gate_reset_after);
  s.Get("kernel", c.kernel);
  s.Get("max_chi2", c.max_chi2);
  s.Finish();
}

/// `odometry` is not a key: it is built from the `estimator` section and the extrinsic.
void Bind(Section s, estimator::WindowEstimatorConfig& c) {
  s.Get("window_size", c.window_size);
  s.Get("max_iterations", c.max_iterations);
  s.Get("prealign", c.prealign);
  s.Get("reassociations", c.reassociations);
  s.Get("edge_threshold_m2", c.edge_threshold_m2);
  s.Get("max_edges_per_sector", c.max_edges_per_sector);
  s.Get("local_map_radius_m", c.local_map_radius_m);
  s.Get("lidar_sigma_m", c.lidar_sigma_m);
  s.Get("huber_m", c.huber_m);
  s.Get("degenerate_eigenvalue", c.degenerate_eigenvalue);
  s.Get("lidar_floor_sigma_m", c.lidar_floor_sigma_m);
  s.Get("lidar_floor_sigma_tilt_rad", c.lidar_floor_sigma_tilt_rad);
  s.Get("lidar_floor_sigma_yaw_rad", c.lidar_floor_sigma_yaw_rad);
  s.Get("estimate_extrinsic", c.estimate_extrinsic);
  s.Get("extrinsic_prior_sigma_m", c.extrinsic_prior_sigma_m);
  s.Get("extrinsic_prior_sigma_rad", c.extrinsic_prior_sigma_rad);
  s.Get("calibrate_extrinsic_s", c.calibrate_extrinsic_s);
  s.Get("calibrate_retry_s", c.calibrate_retry_s);
  s.Get("init_sigma_position_m", c.init_sigma_position_m);
  s.Get("init_sigma_rotation_rad", c.init_sigma_rotation_rad);
  s.Get("init_sigma_velocity_mps", c.init_sigma_velocity_mps);
  s.Get("init_sigma_bias_acc_mps2", c.init_sigma_bias_acc_mps2);
  s.Get("init_sigma_bias_gyro_radps", c.init_sigma_bias_gyro_radps);
  s.Get("bias_prior_sigma_acc_mps2", c.bias_prior_sigma_acc_mps2);
  s.Get("bias_prior_sigma_gyro_radps", c.bias_prior_sigma_gyro_radps);
  s.Get("dynamic_init", c.dynamic_init);
  s.Get("static_max_speed_mps", c.static_max_speed_mps);
  s.Get("covariance", c.covariance);
  s.Get("init_tilt_follows_bias", c.init_tilt_follows_bias);
  s.Get("estimate_gravity_tilt", c.estimate_gravity_tilt);
  Bind(s.Child("bootstrap"), c.bootstrap);
  Bind(s.Child("divergence"), c.divergence);
  Bind(s.Child("wheel"), c.wheel);
  Bind(s.Child("standstill"), c.standstill);
  Bind(s.Child("imu_noise_adapter"), c.imu_noise_adapter);
  Bind(s.Child("time_offset"), c.time_offset);
  Bind(s.Child("visibility"), c.visibility);
  s.Finish();
}

void Bind(Section s, estimator::ScanContextConfig& c) {
  s.Get("rings", c.rings);
  s.Get("sectors", c.sectors);
  s.Get("max_range_m", c.max_range_m);
  s.Get("min_range_m", c.min_range_m);
  s.Get("height_offset_m", c.height_offset_m);
  s.Get("candidates", c.candidates);
  s.Get("max_distance", c.max_distance);
  s.Finish();
}

/// The matchers' own settings (coarse, fine) are not keys.
void Bind(Section s, estimator::LoopClosureConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("descriptor_candidates", c.descriptor_candidates);
  s.Get("max_drift_ratio", c.max_drift_ratio);
  Bind(s.Child("visibility"), c.visibility);
  Bind(s.Child("descriptor"), c.descriptor);
  s.Get("keyframe_distance_m", c.keyframe_distance_m);
  s.Get("keyframe_angle_rad", c.keyframe_angle_rad);
  s.Get("search_radius_m", c.search_radius_m);
  s.Get("min_separation_s", c.min_separation_s);
  s.Get("place_radius_m", c.place_radius_m);
  s.Get("place_angle_rad", c.place_angle_rad);
  s.Get("attempt_every_nodes", c.attempt_every_nodes);
  s.Get("submap_half_width", c.submap_half_width);
  s.Get("inlier_distance_m", c.inlier_distance_m);
  s.Get("min_fitness", c.min_fitness);
  s.Get("min_inliers", c.min_inliers);
  s.Get("min_hessian_eigenvalue", c.min_hessian_eigenvalue);
  s.Get("max_correction_m", c.max_correction_m);
  s.Get("max_correction_rad", c.max_correction_rad);
  s.Get("odometry_sigma_m", c.odometry_sigma_m);
  s.Get("odometry_sigma_rad", c.odometry_sigma_rad);
  s.Get("loop_sigma_m", c.loop_sigma_m);
  s.Get("loop_sigma_rad", c.loop_sigma_rad);
  s.Get("max_loop_chi2", c.max_loop_chi2);
  s.Get("loop_kernel", c.loop_kernel);
  s.Get("max_iterations", c.max_iterations);
  s.Get("output_max_rate_mps", c.output_max_rate_mps);
  s.Get("output_max_rate_radps", c.output_max_rate_radps);
  Bind(s.Child("gnss"), c.gnss);
  s.Finish();
}

/// `registration` is not a key (the daemon uses estimator.loop_closure's).
void Bind(Section s, estimator::LocalizationConfig& c) {
  s.Get("relocalize_max_descriptor_distance", c.relocalize_max_descriptor_distance);
  s.Get("relocalize_candidates", c.relocalize_candidates);
  s.Get("relocalize_max_correction_m", c.relocalize_max_correction_m);
  s.Get("relocalize_max_correction_rad", c.relocalize_max_correction_rad);
  s.Get("confirmations", c.confirmations);
  s.Get("relocalize_every_m", c.relocalize_every_m);
  s.Get("relocalize_every_rad", c.relocalize_every_rad);
  s.Get("track_every_m", c.track_every_m);
  s.Get("track_every_rad", c.track_every_rad);
  s.Get("relocalize_min_margin", c.relocalize_min_margin);
  s.Get("distinct_m", c.distinct_m);
  s.Get("submap_radius_m", c.submap_radius_m);
  s.Get("submap_max_nodes", c.submap_max_nodes);
  s.Get("track_min_fitness", c.track_min_fitness);
  s.Get("track_max_correction_m", c.track_max_correction_m);
  s.Get("track_max_correction_rad", c.track_max_correction_rad);
  s.Get("lost_after_failures", c.lost_after_failures);
  s.Finish();
}

void Bind(Section s, MapFilesConfig& c) {
  s.Get("save_path", c.save_path);
  s.Get("load_path", c.load_path);
  s.Get("localize", c.localize);
  s.Finish();
}

void Bind(Section s, StateConfig& c) {
  s.Get("time_offset_file", c.time_offset_file);
  s.Get("save_period_s", c.save_period_s);
  s.Finish();
}

void Bind(Section s,
          estimator::EstimatorConfig& c,
          estimator::WindowEstimatorConfig& window,
          estimator::LoopClosureConfig& loop_closure,
          estimator::LocalizationConfig& localization) {
  s.Get("mode", c.mode);
  Bind(s.Child("imu_noise"), c.imu_noise);
  Section extrinsic = s.Child("extrinsic_imu_lidar");
  extrinsic.Removed("estimate_online",
                    "use estimator.window.estimate_extrinsic to refine T_imu_lidar in the window, "
                    "or estimator.window.calibrate_extrinsic_s to calibrate it in one batch");
  Bind(extrinsic, c.extrinsic_imu_lidar);
  s.Get("gravity_mps2", c.gravity_mps2);
  s.Get("init_static_duration_s", c.init_static_duration_s);
  s.Get("plane_voxel_m", c.plane_voxel_m);
  s.Get("edge_voxel_m", c.edge_voxel_m);
  s.Get("local_map_radius_m", c.local_map_radius_m);
  s.Get("output_rebase_rate_mps", c.output_rebase_rate_mps);
  s.Get("output_rebase_rate_radps", c.output_rebase_rate_radps);
  s.Removed("window_size", "use estimator.window.window_size instead");
  s.Removed("max_iterations", "use estimator.window.max_iterations instead");
  s.Removed("num_threads",
            "every solve runs on one thread, for deterministic results: delete the line");
  Bind(s.Child("window"), window);
  Bind(s.Child("loop_closure"), loop_closure);
  Bind(s.Child("localization"), localization);
  s.Finish();
}

void Bind(Section s, ipc::FrameNames& c) {
  s.Get("map", c.map);
  s.Get("odom", c.odom);
  s.Get("base_link", c.base_link);
  s.Get("imu", c.imu);
  s.Get("lidar", c.lidar);
  s.Finish();
}

void Bind(Section s, ipc::IpcConfig& c) {
  s.Get("domain_id", c.domain_id);
  s.Get("dds_config_file", c.dds_config_file);
  s.Get("require_loopback", c.require_loopback);
  s.Get("pose_topic", c.pose_topic);
  s.Get("odometry_topic", c.odometry_topic);
  s.Get("health_topic", c.health_topic);
  s.Get("path_topic", c.path_topic);
  s.Get("path_max_poses", c.path_max_poses);
  s.Get("map_topic", c.map_topic);
  s.Get("map_max_points", c.map_max_points);
  s.Get("map_publish_period_s", c.map_publish_period_s);
  s.Get("stamp_clock", c.stamp_clock);
  s.Get("odom_odometry_topic", c.odom_odometry_topic);
  s.Get("initialpose_topic", c.initialpose_topic);
  s.Get("sweep_topic", c.sweep_topic);
  s.Get("tf_topic", c.tf_topic);
  s.Get("tf_static_topic", c.tf_static_topic);
  s.Get("map_odom_period_s", c.map_odom_period_s);
  Bind(s.Child("frames"), c.frames);
  s.Finish();
}

void Bind(Section s, LoggingConfig& c) {
  s.Get("directory", c.directory);
  s.Get("file_name", c.file_name);
  s.Get("file_level", c.file_level);
  s.Get("stderr_level", c.stderr_level);
  s.Get("journald", c.journald);  // auto, or a YAML boolean (yes/on/True… spelled as true/false)
  if (bool on = false; ParseBool(c.journald, &on)) c.journald = on ? "true" : "false";
  s.Get("max_file_size_mb", c.max_file_size_mb);
  s.Get("max_files", c.max_files);
  s.Get("status_period_s", c.status_period_s);
  s.Finish();
}

void Bind(Section s, RecordConfig& c) {
  s.Get("ring", c.ring);
  s.Get("directory", c.directory);
  s.Get("ring_minutes", c.ring_minutes);
  s.Get("segment_s", c.segment_s);
  s.Get("max_disk_mb", c.max_disk_mb);
  s.Get("incident_before_s", c.incident_before_s);
  s.Get("incident_after_s", c.incident_after_s);
  s.Get("incidents_max_count", c.incidents_max_count);
  s.Get("incidents_max_mb", c.incidents_max_mb);
  s.Finish();
}

void Bind(Section s, RealtimeConfig& c) {
  s.Get("enabled", c.enabled);
  s.Get("lock_memory", c.lock_memory);
  s.Get("max_sweep_lag_s", c.max_sweep_lag_s);
  std::vector<ThreadSchedConfig> listed;
  const bool present = s.ForEachChild("threads", [&](Section item) {
    ThreadSchedConfig& t = listed.emplace_back();
    item.Get("name", t.name);
    item.Get("priority", t.priority);
    item.Get("cpu", t.cpu);
    item.Get("nice", t.nice);
    item.Finish();
  });
  if (present) c.threads = std::move(listed);  // the YAML's list replaces the default one
  s.Finish();
}

void Bind(Section s, ControlConfig& c) {
  s.Get("socket", c.socket);
  s.Get("group", c.group);
  s.Get("request_timeout_s", c.request_timeout_s);
  s.Get("command_timeout_s", c.command_timeout_s);
  s.Get("max_clients", c.max_clients);
  s.Finish();
}

void BindRoot(Section root, DaemonConfig& c, Context& ctx) {
  c.config_version = -1;
  root.Get("config_version", c.config_version);
  if (c.config_version == -1 && ctx.marks.count("config_version") == 0) {
    ctx.Error(YAML::Mark::null_mark(), "config_version",
              "missing required key (this build reads config_version: " +
                  std::to_string(kConfigVersion) + ")");
    c.config_version = kConfigVersion;  // reported once, not again by Validate()
  }
  Bind(root.Child("lidar"), c.lidar);
  Bind(root.Child("imu"), c.imu);
  Bind(root.Child("can"), c.can);
  Bind(root.Child("estimator"), c.estimator, c.window, c.loop_closure, c.localization);
  Bind(root.Child("map"), c.map);
  Bind(root.Child("state"), c.state);
  Bind(root.Child("ipc"), c.ipc);
  Bind(root.Child("logging"), c.logging);
  Bind(root.Child("record"), c.record);
  Bind(root.Child("realtime"), c.realtime);
  Bind(root.Child("control"), c.control);
  root.Finish();
}

/// Relative paths in the file are relative to the file's directory.
void ResolvePaths(DaemonConfig& c, const std::filesystem::path& base_dir) {
  auto resolve = [&](std::string& p) {
    if (!p.empty() && std::filesystem::path(p).is_relative()) {
      p = (base_dir / p).lexically_normal().string();
    }
  };
  resolve(c.logging.directory);
  resolve(c.record.directory);
  resolve(c.ipc.dds_config_file);
  resolve(c.map.save_path);
  resolve(c.map.load_path);
  resolve(c.state.time_offset_file);
  resolve(c.control.socket);
}

/// Validate() results carry key names only; add the place of each key in the file.
void AddValidationErrors(const DaemonConfig& c, Context& ctx) {
  for (const ConfigIssue& issue : c.Validate()) {
    auto it = ctx.marks.find(issue.key);
    if (it != ctx.marks.end()) {
      ctx.Error(it->second, issue.key, issue.reason);
    } else {
      ctx.Error(YAML::Mark::null_mark(), issue.key, issue.reason + " (default value)");
    }
  }
}

}  // namespace

std::string ConfigError::ToString() const {
  std::ostringstream os;
  os << file;
  if (line > 0) os << ':' << line << ':' << column;
  os << ": ";
  if (!key.empty()) os << key << ": ";
  os << reason;
  return os.str();
}

std::string LoadedConfig::ErrorReport() const {
  std::string report;
  for (const auto& e : errors) report += e.ToString() + "\n";
  return report;
}

LoadedConfig LoadConfigText(const std::string& yaml_text,
                            const std::string& display_name,
                            const std::filesystem::path& base_dir) {
  LoadedConfig result;
  Context ctx{display_name, {}, {}};
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    ctx.Error(e.mark, "", "YAML syntax error: " + e.msg);
    result.errors = std::move(ctx.errors);
    return result;
  }
  if (!root.IsMap()) {
    ctx.Error(root.Mark(), "", "expected a mapping of sections at the top, got " + Describe(root));
    result.errors = std::move(ctx.errors);
    return result;
  }
  BindRoot(Section(root, "", &ctx), result.config, ctx);
  ResolvePaths(result.config, base_dir);
  AddValidationErrors(result.config, ctx);
  std::stable_sort(ctx.errors.begin(), ctx.errors.end(),
                   [](const ConfigError& a, const ConfigError& b) { return a.line < b.line; });
  result.errors = std::move(ctx.errors);
  return result;
}

LoadedConfig LoadConfigFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    LoadedConfig result;
    result.errors.push_back({path.string(), 0, 0, "", "cannot open the configuration file"});
    return result;
  }
  std::ostringstream text;
  text << in.rdbuf();
  const std::filesystem::path base = std::filesystem::absolute(path).parent_path();
  return LoadConfigText(text.str(), path.string(), base);
}

}  // namespace swlio::daemon
