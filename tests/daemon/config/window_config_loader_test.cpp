// estimator.window: the sliding-window estimator's options in the YAML configuration.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "swlio/daemon/config/config_loader.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

using estimator::WindowEstimatorConfig;
using ::testing::HasSubstr;

LoadedConfig Load(const std::string& text) {
  return LoadConfigText(text, "test.yaml", "/etc/swlio");
}

/// One object: a temporary of this large config made GCC 12 warn about maybe-uninitialized
/// strings (as in swlio-run).
const WindowEstimatorConfig& Defaults() {
  static const WindowEstimatorConfig defaults;
  return defaults;
}

/// Every field the file sets (odometry is built by the user, not read).
void ExpectSameWindow(const WindowEstimatorConfig& a, const WindowEstimatorConfig& b) {
  EXPECT_EQ(a.window_size, b.window_size);
  EXPECT_EQ(a.max_iterations, b.max_iterations);
  EXPECT_EQ(a.prealign, b.prealign);
  EXPECT_EQ(a.reassociations, b.reassociations);
  EXPECT_EQ(a.edge_threshold_m2, b.edge_threshold_m2);
  EXPECT_EQ(a.max_edges_per_sector, b.max_edges_per_sector);
  EXPECT_EQ(a.local_map_radius_m, b.local_map_radius_m);
  EXPECT_EQ(a.lidar_sigma_m, b.lidar_sigma_m);
  EXPECT_EQ(a.huber_m, b.huber_m);
  EXPECT_EQ(a.degenerate_eigenvalue, b.degenerate_eigenvalue);
  EXPECT_EQ(a.lidar_floor_sigma_m, b.lidar_floor_sigma_m);
  EXPECT_EQ(a.lidar_floor_sigma_tilt_rad, b.lidar_floor_sigma_tilt_rad);
  EXPECT_EQ(a.lidar_floor_sigma_yaw_rad, b.lidar_floor_sigma_yaw_rad);
  EXPECT_EQ(a.estimate_extrinsic, b.estimate_extrinsic);
  EXPECT_EQ(a.extrinsic_prior_sigma_m, b.extrinsic_prior_sigma_m);
  EXPECT_EQ(a.extrinsic_prior_sigma_rad, b.extrinsic_prior_sigma_rad);
  EXPECT_EQ(a.calibrate_extrinsic_s, b.calibrate_extrinsic_s);
  EXPECT_EQ(a.estimate_gravity_tilt, b.estimate_gravity_tilt);
  EXPECT_EQ(a.calibrate_retry_s, b.calibrate_retry_s);
  EXPECT_EQ(a.init_sigma_position_m, b.init_sigma_position_m);
  EXPECT_EQ(a.init_sigma_rotation_rad, b.init_sigma_rotation_rad);
  EXPECT_EQ(a.init_sigma_velocity_mps, b.init_sigma_velocity_mps);
  EXPECT_EQ(a.init_sigma_bias_acc_mps2, b.init_sigma_bias_acc_mps2);
  EXPECT_EQ(a.init_sigma_bias_gyro_radps, b.init_sigma_bias_gyro_radps);
  EXPECT_EQ(a.bias_prior_sigma_acc_mps2, b.bias_prior_sigma_acc_mps2);
  EXPECT_EQ(a.bias_prior_sigma_gyro_radps, b.bias_prior_sigma_gyro_radps);
  EXPECT_EQ(a.dynamic_init, b.dynamic_init);
  EXPECT_EQ(a.static_max_speed_mps, b.static_max_speed_mps);
  const auto &ba = a.bootstrap, &bb = b.bootstrap;
  EXPECT_EQ(ba.window_frames, bb.window_frames);
  EXPECT_EQ(ba.imu_buffer_s, bb.imu_buffer_s);
  EXPECT_EQ(ba.max_imu_lag_s, bb.max_imu_lag_s);
  EXPECT_EQ(ba.max_sweep_gap_s, bb.max_sweep_gap_s);
  EXPECT_EQ(ba.max_speed_mps, bb.max_speed_mps);
  EXPECT_EQ(ba.refine_deskew_m, bb.refine_deskew_m);
  EXPECT_EQ(ba.deskew_refinements, bb.deskew_refinements);
  EXPECT_EQ(ba.line_min_ratio, bb.line_min_ratio);
  const auto &ia = ba.initializer, &ib = bb.initializer;
  EXPECT_EQ(ia.min_frames, ib.min_frames);
  EXPECT_EQ(ia.position_sigma_m, ib.position_sigma_m);
  EXPECT_EQ(ia.rotation_sigma_rad, ib.rotation_sigma_rad);
  EXPECT_EQ(ia.acc_bias_prior_sigma_mps2, ib.acc_bias_prior_sigma_mps2);
  EXPECT_EQ(ia.max_acc_bias_std_mps2, ib.max_acc_bias_std_mps2);
  EXPECT_EQ(ia.require_acc_bias, ib.require_acc_bias);
  EXPECT_EQ(ia.max_normalized_rms, ib.max_normalized_rms);
  EXPECT_EQ(ia.max_gravity_norm_error_mps2, ib.max_gravity_norm_error_mps2);
  EXPECT_EQ(ia.max_gyro_bias_radps, ib.max_gyro_bias_radps);
  EXPECT_EQ(ia.max_gravity_tilt_std_rad, ib.max_gravity_tilt_std_rad);
  EXPECT_EQ(ia.max_velocity_std_mps, ib.max_velocity_std_mps);
  EXPECT_EQ(ia.gyro_iterations, ib.gyro_iterations);
  EXPECT_EQ(ia.gravity_iterations, ib.gravity_iterations);
  const auto &sa = a.standstill, &sb = b.standstill;
  EXPECT_EQ(sa.enabled, sb.enabled);
  EXPECT_EQ(sa.imu_window_s, sb.imu_window_s);
  EXPECT_EQ(sa.max_acc_std_mps2, sb.max_acc_std_mps2);
  EXPECT_EQ(sa.max_gyro_std_radps, sb.max_gyro_std_radps);
  EXPECT_EQ(sa.max_specific_force_error_mps2, sb.max_specific_force_error_mps2);
  EXPECT_EQ(sa.max_rate_radps, sb.max_rate_radps);
  EXPECT_EQ(sa.max_lidar_speed_mps, sb.max_lidar_speed_mps);
  EXPECT_EQ(sa.sigma_velocity_mps, sb.sigma_velocity_mps);
}

TEST(WindowConfig, AbsentSectionGivesTheStructDefaults) {
  const LoadedConfig loaded = Load("config_version: 1\n");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  ExpectSameWindow(loaded.config.window, Defaults());
}

// The shipped file documents the defaults: loading it changes nothing.
TEST(WindowConfig, ShippedConfigStatesTheStructDefaults) {
  const LoadedConfig loaded = LoadConfigFile(test::SourceDir() / "config" / "swlio.yaml");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  ExpectSameWindow(loaded.config.window, Defaults());
}

TEST(WindowConfig, EveryKeyIsStored) {
  const LoadedConfig loaded = Load(R"(config_version: 1
estimator:
  window:
    window_size: 7
    max_iterations: 6
    prealign: false
    reassociations: 2
    edge_threshold_m2: 0.15
    max_edges_per_sector: 40
    local_map_radius_m: 120
    lidar_sigma_m: 0.04
    huber_m: 0.2
    degenerate_eigenvalue: 8
    lidar_floor_sigma_m: 0.02
    lidar_floor_sigma_tilt_rad: 0.04
    lidar_floor_sigma_yaw_rad: 0.005
    estimate_extrinsic: true
    extrinsic_prior_sigma_m: 0.03
    extrinsic_prior_sigma_rad: 0.02
    calibrate_extrinsic_s: 40
    calibrate_retry_s: 3
    init_sigma_position_m: 0.002
    init_sigma_rotation_rad: 0.003
    init_sigma_velocity_mps: 0.06
    init_sigma_bias_acc_mps2: 0.07
    init_sigma_bias_gyro_radps: 0.008
    bias_prior_sigma_acc_mps2: 0.0
    bias_prior_sigma_gyro_radps: 0.01
    dynamic_init: false
    estimate_gravity_tilt: false
    static_max_speed_mps: 0.1
    bootstrap:
      window_frames: 25
      imu_buffer_s: 12
      max_imu_lag_s: 0.03
      max_sweep_gap_s: 0.5
      max_speed_mps: 4
      refine_deskew_m: 0.02
      deskew_refinements: 2
      line_min_ratio: 4
      initializer:
        min_frames: 6
        position_sigma_m: 0.03
        rotation_sigma_rad: 0.004
        acc_bias_prior_sigma_mps2: 0.06
        max_acc_bias_std_mps2: 0.04
        require_acc_bias: true
        max_normalized_rms: 2.5
        max_gravity_norm_error_mps2: 0.4
        max_gyro_bias_radps: 0.03
        max_gravity_tilt_std_rad: 0.03
        max_velocity_std_mps: 0.2
        gyro_iterations: 4
        gravity_iterations: 5
    standstill:
      enabled: false
      imu_window_s: 0.7
      max_acc_std_mps2: 0.04
      max_gyro_std_radps: 0.02
      max_specific_force_error_mps2: 0.06
      max_rate_radps: 0.004
      max_lidar_speed_mps: 0.05
      sigma_velocity_mps: 0.002
)");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  WindowEstimatorConfig want;
  want.window_size = 7;
  want.max_iterations = 6;
  want.prealign = false;
  want.reassociations = 2;
  want.edge_threshold_m2 = 0.15;
  want.max_edges_per_sector = 40;
  want.local_map_radius_m = 120;
  want.lidar_sigma_m = 0.04;
  want.huber_m = 0.2;
  want.degenerate_eigenvalue = 8;
  want.lidar_floor_sigma_m = 0.02;
  want.lidar_floor_sigma_tilt_rad = 0.04;
  want.lidar_floor_sigma_yaw_rad = 0.005;
  want.estimate_extrinsic = true;
  want.extrinsic_prior_sigma_m = 0.03;
  want.extrinsic_prior_sigma_rad = 0.02;
  want.calibrate_extrinsic_s = 40;
  want.calibrate_retry_s = 3;
  want.init_sigma_position_m = 0.002;
  want.init_sigma_rotation_rad = 0.003;
  want.init_sigma_velocity_mps = 0.06;
  want.init_sigma_bias_acc_mps2 = 0.07;
  want.init_sigma_bias_gyro_radps = 0.008;
  want.bias_prior_sigma_acc_mps2 = 0.0;
  want.bias_prior_sigma_gyro_radps = 0.01;
  want.dynamic_init = false;
  want.estimate_gravity_tilt = false;
  want.static_max_speed_mps = 0.1;
  want.bootstrap.window_frames = 25;
  want.bootstrap.imu_buffer_s = 12;
  want.bootstrap.max_imu_lag_s = 0.03;
  want.bootstrap.max_sweep_gap_s = 0.5;
  want.bootstrap.max_speed_mps = 4;
  want.bootstrap.refine_deskew_m = 0.02;
  want.bootstrap.deskew_refinements = 2;
  want.bootstrap.line_min_ratio = 4;
  auto& init = want.bootstrap.initializer;
  init.min_frames = 6;
  init.position_sigma_m = 0.03;
  init.rotation_sigma_rad = 0.004;
  init.acc_bias_prior_sigma_mps2 = 0.06;
  init.max_acc_bias_std_mps2 = 0.04;
  init.require_acc_bias = true;
  init.max_normalized_rms = 2.5;
  init.max_gravity_norm_error_mps2 = 0.4;
  init.max_gyro_bias_radps = 0.03;
  init.max_gravity_tilt_std_rad = 0.03;
  init.max_velocity_std_mps = 0.2;
  init.gyro_iterations = 4;
  init.gravity_iterations = 5;
  want.standstill = {.enabled = false,  // the default is on
                     .imu_window_s = 0.7,
                     .max_acc_std_mps2 = 0.04,
                     .max_gyro_std_radps = 0.02,
                     .max_specific_force_error_mps2 = 0.06,
                     .max_rate_radps = 0.004,
                     .max_lidar_speed_mps = 0.05,
                     .sigma_velocity_mps = 0.002};
  ExpectSameWindow(loaded.config.window, want);
}

TEST(WindowConfig, RuleViolationsNameKeyLineAndColumn) {
  const LoadedConfig loaded = Load(R"(config_version: 1
estimator:
  window:
    window_size: 1
    lidar_sigma_m: -0.05
    extrinsic_prior_sigma_rad: 0
    bias_prior_sigma_acc_mps2: -1
    bootstrap:
      window_frames: 4
      initializer:
        min_frames: 5
        rotation_sigma_rad: -0.1
    edge_threshold_m2: 0
    max_edges_per_sector: 1
    local_map_radius_m: 5
)");
  ASSERT_EQ(loaded.errors.size(), 9u) << loaded.ErrorReport();
  EXPECT_EQ(loaded.errors[0].ToString(),
            "test.yaml:4:5: estimator.window.window_size: must be in [2, 50], got 1");
  EXPECT_EQ(loaded.errors[1].ToString(),
            "test.yaml:5:5: estimator.window.lidar_sigma_m: must be > 0, got -0.05");
  EXPECT_EQ(loaded.errors[2].key, "estimator.window.extrinsic_prior_sigma_rad");
  EXPECT_EQ(loaded.errors[2].line, 6);
  EXPECT_EQ(loaded.errors[3].key, "estimator.window.bias_prior_sigma_acc_mps2");
  EXPECT_THAT(loaded.errors[3].reason, HasSubstr("must be in [0, 10], got -1"));
  // Cross-field: fewer bootstrap poses than the initializer needs.
  EXPECT_EQ(loaded.errors[4].key, "estimator.window.bootstrap.window_frames");
  EXPECT_EQ(loaded.errors[4].line, 9);
  EXPECT_THAT(loaded.errors[4].reason, HasSubstr("initializer.min_frames"));
  EXPECT_EQ(loaded.errors[5].ToString(),
            "test.yaml:12:9: estimator.window.bootstrap.initializer.rotation_sigma_rad: must be "
            "> 0, got -0.1");
  EXPECT_EQ(loaded.errors[6].ToString(),
            "test.yaml:13:5: estimator.window.edge_threshold_m2: must be in [1e-06, 100], got 0");
  // Fewer than the sharp edges (max_sharp_edges_per_sector, 2) it includes.
  EXPECT_EQ(loaded.errors[7].ToString(),
            "test.yaml:14:5: estimator.window.max_edges_per_sector: must be in [2, 10000], got 1");
  EXPECT_EQ(loaded.errors[8].ToString(),
            "test.yaml:15:5: estimator.window.local_map_radius_m: must be in [10, 500], got 5");
}

TEST(WindowConfig, StandstillRangesNameKeyLineAndColumn) {
  const LoadedConfig loaded = Load(R"(config_version: 1
estimator:
  window:
    standstill:
      enabled: true
      sigma_velocity_mps: 0
      max_rate_radps: -0.1
)");
  ASSERT_EQ(loaded.errors.size(), 2u) << loaded.ErrorReport();
  EXPECT_EQ(loaded.errors[0].key, "estimator.window.standstill.sigma_velocity_mps");
  EXPECT_EQ(loaded.errors[0].line, 6);
  EXPECT_EQ(loaded.errors[1].ToString(),
            "test.yaml:7:7: estimator.window.standstill.max_rate_radps: must be in [0, 0.5], got "
            "-0.1");
}

TEST(WindowConfig, TypeErrorsAndUnknownKeysAreReported) {
  const LoadedConfig loaded = Load(R"(config_version: 1
estimator:
  window:
    window_size: -5
    max_iterations: 2.5
    dynamic_init: sometimes
    lidar_sigma: 0.05
    odometry: {}
    bootstrap: 3
)");
  ASSERT_EQ(loaded.errors.size(), 6u) << loaded.ErrorReport();
  EXPECT_EQ(loaded.errors[0].key, "estimator.window.window_size");
  EXPECT_THAT(loaded.errors[0].reason, HasSubstr("expected an integer in [0, "));
  EXPECT_EQ(loaded.errors[1].key, "estimator.window.max_iterations");
  EXPECT_THAT(loaded.errors[1].reason, HasSubstr("got '2.5'"));
  EXPECT_EQ(loaded.errors[2].key, "estimator.window.dynamic_init");
  EXPECT_THAT(loaded.errors[2].reason, HasSubstr("true or false"));
  EXPECT_EQ(loaded.errors[3].key, "estimator.window.lidar_sigma");
  EXPECT_THAT(loaded.errors[3].reason, HasSubstr("did you mean 'lidar_sigma_m'?"));
  EXPECT_EQ(loaded.errors[4].key, "estimator.window.odometry");  // built by the user, not read
  EXPECT_THAT(loaded.errors[4].reason, HasSubstr("unknown key"));
  EXPECT_EQ(loaded.errors[5].key, "estimator.window.bootstrap");
  EXPECT_EQ(loaded.errors[5].line, 9);
}

// The window's own `odometry` holds defaults in a DaemonConfig and is not the file's business:
// an invalid one is not reported under estimator.window (the user replaces it).
TEST(WindowConfig, OdometryIsNotValidatedHere) {
  DaemonConfig config;
  config.window.odometry.estimator.gravity_mps2 = -1.0;
  ASSERT_FALSE(config.window.Validate().empty());  // the window's own Validate() does see it
  for (const ConfigIssue& issue : config.Validate()) {
    EXPECT_EQ(issue.key.find("estimator.window.odometry"), std::string::npos) << issue.key;
  }
  config.window.window_size = 0;
  bool reported = false;
  for (const ConfigIssue& issue : config.Validate()) {
    reported = reported || issue.key == "estimator.window.window_size";
  }
  EXPECT_TRUE(reported);
}

}  // namespace
}  // namespace swlio::daemon
