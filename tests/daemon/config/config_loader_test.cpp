#include "swlio/daemon/config/config_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <utility>

#include "test_data.h"

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;

LoadedConfig Load(const std::string& text) {
  return LoadConfigText(text, "test.yaml", "/etc/swlio");
}

/// The single error of a load, or a failure when there is not exactly one.
ConfigError OnlyError(const LoadedConfig& loaded) {
  EXPECT_EQ(loaded.errors.size(), 1u) << loaded.ErrorReport();
  return loaded.errors.empty() ? ConfigError{} : loaded.errors.front();
}

TEST(ConfigLoader, ShippedConfigIsValid) {
  const auto path = test::SourceDir() / "config" / "swlio.yaml";
  const LoadedConfig loaded = LoadConfigFile(path);
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  EXPECT_EQ(loaded.config.lidar.model, "rs16");
  EXPECT_EQ(loaded.config.lidar.msop_port, 6699);
  EXPECT_EQ(loaded.config.imu.baud, 921600);
  EXPECT_EQ(loaded.config.window.window_size, 5u);
  // Relative paths are resolved against the file's directory.
  EXPECT_EQ(loaded.config.ipc.dds_config_file,
            (std::filesystem::absolute(path).parent_path() / "cyclonedds-loopback.xml")
                .lexically_normal()
                .string());
}

TEST(ConfigLoader, MinimalFileGivesDefaults) {
  const LoadedConfig loaded = Load("config_version: 1\n");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  const DaemonConfig defaults;
  EXPECT_EQ(loaded.config.lidar.max_range_m, defaults.lidar.max_range_m);
  EXPECT_EQ(loaded.config.lidar.vertical_angles_deg, defaults.lidar.vertical_angles_deg);
  EXPECT_EQ(loaded.config.estimator.mode, "tightly-coupled");
  EXPECT_EQ(loaded.config.logging.directory, "/var/log/swlio");
  EXPECT_EQ(loaded.config.ipc.dds_config_file, "/etc/swlio/cyclonedds-loopback.xml");
}

// The shipped file documents the estimator's defaults: loading it changes nothing, to the last
// bit. The daemon loads the file and swlio-run without --config takes the struct defaults, and
// the long drives are chaotic in them: with the gyro noise density rounded to 1.74533e-4 rad/s/√Hz
// (2.6e-7 relative) the two parted 27 s into loop943 seed 2 and ended at 0.117 against 0.240 m
// APE.
TEST(ConfigLoader, ShippedConfigStatesTheEstimatorDefaults) {
  const LoadedConfig loaded = LoadConfigFile(test::SourceDir() / "config" / "swlio.yaml");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  const estimator::EstimatorConfig& got = loaded.config.estimator;
  const estimator::EstimatorConfig want;
  EXPECT_EQ(got.imu_noise.acc_noise_density_mps2_per_sqrthz,
            want.imu_noise.acc_noise_density_mps2_per_sqrthz);
  EXPECT_EQ(got.imu_noise.gyro_noise_density_radps_per_sqrthz,
            want.imu_noise.gyro_noise_density_radps_per_sqrthz);
  EXPECT_EQ(got.imu_noise.acc_bias_random_walk_mps3_per_sqrthz,
            want.imu_noise.acc_bias_random_walk_mps3_per_sqrthz);
  EXPECT_EQ(got.imu_noise.gyro_bias_random_walk_radps2_per_sqrthz,
            want.imu_noise.gyro_bias_random_walk_radps2_per_sqrthz);
  EXPECT_EQ(got.extrinsic_imu_lidar.translation_m, want.extrinsic_imu_lidar.translation_m);
  EXPECT_EQ(got.extrinsic_imu_lidar.rotation_rpy_deg, want.extrinsic_imu_lidar.rotation_rpy_deg);
  EXPECT_EQ(got.gravity_mps2, want.gravity_mps2);
  EXPECT_EQ(got.init_static_duration_s, want.init_static_duration_s);
  EXPECT_EQ(got.plane_voxel_m, want.plane_voxel_m);
  EXPECT_EQ(got.edge_voxel_m, want.edge_voxel_m);
  EXPECT_EQ(got.local_map_radius_m, want.local_map_radius_m);
}

TEST(ConfigLoader, GoodValuesAreStored) {
  const LoadedConfig loaded = Load(R"(config_version: 1
lidar:
  msop_port: 2244
  cut_angle_deg: 90.5
  vertical_angles_deg: [-15, -14, -13, -12, -11, -10, -9, -8, -7, -6, -5, -4, -3, -2, -1, 0]
imu:
  configure_on_start: no
estimator:
  extrinsic_imu_lidar:
    translation_m: [0.1, -0.02, 0.3]
logging:
  directory: logs
)");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  EXPECT_EQ(loaded.config.lidar.msop_port, 2244);
  EXPECT_DOUBLE_EQ(loaded.config.lidar.cut_angle_deg, 90.5);
  EXPECT_EQ(loaded.config.lidar.vertical_angles_deg[1], -14.0);
  EXPECT_FALSE(loaded.config.imu.configure_on_start);
  EXPECT_DOUBLE_EQ(loaded.config.estimator.extrinsic_imu_lidar.translation_m[2], 0.3);
  EXPECT_EQ(loaded.config.logging.directory, "/etc/swlio/logs");
}

TEST(ConfigLoader, JournaldIsAutoTrueOrFalse) {
  EXPECT_EQ(Load("config_version: 1\n").config.logging.journald, "auto");
  EXPECT_EQ(Load("config_version: 1\n").config.logging.stderr_level, "auto");
  const std::array<std::pair<const char*, const char*>, 5> spellings = {
      {{"auto", "auto"}, {"true", "true"}, {"false", "false"}, {"yes", "true"}, {"off", "false"}}};
  for (const auto& [text, stored] : spellings) {
    const LoadedConfig loaded =
        Load(std::string("config_version: 1\nlogging:\n  journald: ") + text + "\n");
    ASSERT_TRUE(loaded.ok()) << text << ": " << loaded.ErrorReport();
    EXPECT_EQ(loaded.config.logging.journald, stored) << text;
  }
  const ConfigError e = OnlyError(Load("config_version: 1\nlogging:\n  journald: maybe\n"));
  EXPECT_EQ(e.key, "logging.journald");
  EXPECT_EQ(e.line, 3);
  EXPECT_THAT(e.reason, HasSubstr("must be auto, true or false, got 'maybe'"));
  const ConfigError level = OnlyError(Load("config_version: 1\nlogging:\n  stderr_level: loud\n"));
  EXPECT_EQ(level.key, "logging.stderr_level");
  EXPECT_THAT(level.reason, HasSubstr("must be auto, trace"));
  EXPECT_TRUE(Load("config_version: 1\nlogging:\n  stderr_level: warn\n").ok());
}

// lidar.lens_offset_m: absent, the model's vendor value (rs_driver's RX for the RoboSense
// models, none for Velodyne); given, that value for a unit calibrated otherwise; bounded.
TEST(ConfigLoader, LensOffsetDefaultsToTheModelsVendorValue) {
  const std::array<std::pair<const char*, double>, 3> vendor = {
      {{"rs16", 0.03825}, {"helios16p", 0.03498}, {"vlp16", 0.0}}};
  for (const auto& [model, lens_m] : vendor) {
    const LoadedConfig loaded =
        Load(std::string("config_version: 1\nlidar:\n  model: ") + model + "\n");
    ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
    EXPECT_EQ(loaded.config.lidar.EffectiveLensOffsetM(), lens_m) << model;
  }
  const LoadedConfig given = Load("config_version: 1\nlidar:\n  lens_offset_m: 0.0391\n");
  ASSERT_TRUE(given.ok()) << given.ErrorReport();
  EXPECT_EQ(given.config.lidar.EffectiveLensOffsetM(), 0.0391);
  const ConfigError e = OnlyError(Load("config_version: 1\nlidar:\n  lens_offset_m: -0.01\n"));
  EXPECT_EQ(e.key, "lidar.lens_offset_m");
  EXPECT_EQ(e.line, 3);
}

TEST(ConfigLoader, MissingVersionIsAnError) {
  const ConfigError e = OnlyError(Load("lidar:\n  msop_port: 2244\n"));
  EXPECT_EQ(e.key, "config_version");
  EXPECT_THAT(e.reason, HasSubstr("missing required key"));
}

TEST(ConfigLoader, WrongVersionNamesKeyAndLine) {
  const ConfigError e = OnlyError(Load("# comment\nconfig_version: 7\n"));
  EXPECT_EQ(e.key, "config_version");
  EXPECT_EQ(e.line, 2);
}

TEST(ConfigLoader, MistypedValueNamesKeyAndLine) {
  const ConfigError e = OnlyError(Load("config_version: 1\nlidar:\n  msop_port: fast\n"));
  EXPECT_EQ(e.key, "lidar.msop_port");
  EXPECT_EQ(e.line, 3);
  EXPECT_EQ(e.column, 14);
  EXPECT_THAT(e.reason, HasSubstr("expected an integer in [0, 65535], got 'fast'"));
  EXPECT_EQ(e.ToString(),
            "test.yaml:3:14: lidar.msop_port: expected an integer in [0, 65535], got 'fast'");
}

TEST(ConfigLoader, MistypedKindsAreReported) {
  const LoadedConfig loaded = Load(R"(config_version: 1
lidar:
  msop_port: 70000
  max_range_m: [1, 2]
  vertical_angles_deg: [1, 2, 3]
imu:
  configure_on_start: maybe
  baud: 9600.5
can: 5
)");
  ASSERT_EQ(loaded.errors.size(), 6u) << loaded.ErrorReport();
  EXPECT_EQ(loaded.errors[0].key, "lidar.msop_port");
  EXPECT_EQ(loaded.errors[1].key, "lidar.max_range_m");
  EXPECT_THAT(loaded.errors[1].reason, HasSubstr("got a list"));
  EXPECT_EQ(loaded.errors[2].key, "lidar.vertical_angles_deg");
  EXPECT_THAT(loaded.errors[2].reason, HasSubstr("list of 16 numbers"));
  EXPECT_EQ(loaded.errors[3].key, "imu.configure_on_start");
  EXPECT_EQ(loaded.errors[4].key, "imu.baud");
  EXPECT_EQ(loaded.errors[5].key, "can");
  EXPECT_EQ(loaded.errors[5].line, 9);
}

TEST(ConfigLoader, OutOfRangeValueNamesKeyLineAndRule) {
  const ConfigError e = OnlyError(Load("config_version: 1\nlidar:\n  max_range_m: 500\n"));
  EXPECT_EQ(e.key, "lidar.max_range_m");
  EXPECT_EQ(e.line, 3);
  EXPECT_THAT(e.reason, HasSubstr("must be in [1, 300], got 500"));
}

TEST(ConfigLoader, UnknownKeysAreErrorsWithSuggestions) {
  const LoadedConfig loaded = Load(R"(config_version: 1
lidar:
  max_rang_m: 100
estimator:
  imu_noise:
    gyro_noise: 0.1
lidars: {}
)");
  ASSERT_EQ(loaded.errors.size(), 3u) << loaded.ErrorReport();
  EXPECT_EQ(loaded.errors[0].key, "lidar.max_rang_m");
  EXPECT_EQ(loaded.errors[0].line, 3);
  EXPECT_THAT(loaded.errors[0].reason, HasSubstr("unknown key (did you mean 'max_range_m'?)"));
  EXPECT_EQ(loaded.errors[1].key, "estimator.imu_noise.gyro_noise");
  EXPECT_EQ(loaded.errors[1].line, 6);
  EXPECT_EQ(loaded.errors[2].key, "lidars");
  EXPECT_THAT(loaded.errors[2].reason, HasSubstr("did you mean 'lidar'"));
}

// ipc.stamp_clock: realtime by default (ROS 2 time), monotonic on request, nothing else.
TEST(ConfigLoader, StampClockIsRealtimeOrMonotonic) {
  EXPECT_EQ(Load("config_version: 1\n").config.ipc.stamp_clock, "realtime");
  const LoadedConfig monotonic = Load("config_version: 1\nipc:\n  stamp_clock: monotonic\n");
  ASSERT_TRUE(monotonic.ok()) << monotonic.ErrorReport();
  EXPECT_EQ(monotonic.config.ipc.stamp_clock, "monotonic");
  const ConfigError e = OnlyError(Load("config_version: 1\nipc:\n  stamp_clock: gps\n"));
  EXPECT_EQ(e.key, "ipc.stamp_clock");
  EXPECT_EQ(e.line, 3);
  EXPECT_THAT(e.reason, HasSubstr("realtime or monotonic"));
}

// ipc.frames: REP 105's names by default; tf2 frame ids only (no leading '/'), all different.
TEST(ConfigLoader, FrameNamesAreTf2FrameIdsAndDistinct) {
  const LoadedConfig defaults = Load("config_version: 1\n");
  ASSERT_TRUE(defaults.ok()) << defaults.ErrorReport();
  EXPECT_EQ(defaults.config.ipc.frames.map, "map");
  EXPECT_EQ(defaults.config.ipc.frames.odom, "odom");
  EXPECT_EQ(defaults.config.ipc.frames.base_link, "base_link");
  EXPECT_EQ(defaults.config.ipc.frames.imu, "imu_link");
  EXPECT_EQ(defaults.config.ipc.frames.lidar, "lidar_link");
  const LoadedConfig renamed =
      Load("config_version: 1\nipc:\n  frames:\n    base_link: robot1/base_footprint\n");
  ASSERT_TRUE(renamed.ok()) << renamed.ErrorReport();
  EXPECT_EQ(renamed.config.ipc.frames.base_link, "robot1/base_footprint");
  const ConfigError slash =
      OnlyError(Load("config_version: 1\nipc:\n  frames:\n    odom: /odom\n"));
  EXPECT_EQ(slash.key, "ipc.frames.odom");
  EXPECT_THAT(slash.reason, HasSubstr("no leading '/'"));
  const ConfigError same = OnlyError(Load("config_version: 1\nipc:\n  frames:\n    odom: map\n"));
  EXPECT_EQ(same.key, "ipc.frames.odom");
  EXPECT_THAT(same.reason, HasSubstr("must differ from map"));
  const ConfigError period = OnlyError(Load("config_version: 1\nipc:\n  map_odom_period_s: 2\n"));
  EXPECT_EQ(period.key, "ipc.map_odom_period_s");
}

TEST(ConfigLoader, CrossFieldRulesAndEveryErrorAreReported) {
  const LoadedConfig loaded = Load(R"(config_version: 1
lidar:
  msop_port: 7788
  min_range_m: 5
  max_range_m: 4
estimator:
  mode: fast
  init_static_duration_s: 0.1
logging:
  file_level: verbose
)");
  ASSERT_EQ(loaded.errors.size(), 5u) << loaded.ErrorReport();
  EXPECT_EQ(loaded.errors[0].key, "lidar.difop_port");  // default value clashes
  EXPECT_EQ(loaded.errors[0].line, 0);
  EXPECT_THAT(loaded.errors[0].reason, HasSubstr("(default value)"));
  EXPECT_EQ(loaded.errors[1].key, "lidar.max_range_m");
  EXPECT_EQ(loaded.errors[1].line, 5);
  EXPECT_EQ(loaded.errors[2].key, "estimator.mode");
  EXPECT_EQ(loaded.errors[3].key, "estimator.init_static_duration_s");
  EXPECT_EQ(loaded.errors[4].key, "logging.file_level");
  EXPECT_EQ(loaded.errors[4].line, 10);
}

TEST(ConfigLoader, LidarPortsAmongTheDdsDomainsPortsAreRefused) {
  // Domain 2's ports are 7900–8011 (7400 + 250·2 + 0..111): DDS discovery would arrive there.
  const LoadedConfig clash = Load(R"(config_version: 1
lidar:
  msop_port: 7910
  difop_port: 8011
ipc:
  domain_id: 2
)");
  ASSERT_EQ(clash.errors.size(), 2u) << clash.ErrorReport();
  EXPECT_EQ(clash.errors[0].key, "lidar.msop_port");
  EXPECT_EQ(clash.errors[0].line, 3);
  EXPECT_THAT(clash.errors[0].reason, HasSubstr("DDS domain 2's ports (7900–8011)"));
  EXPECT_EQ(clash.errors[1].key, "lidar.difop_port");
  // The same ports with domain 0 (7400–7511), and the factory ports 6699 / 7788 with domain 1
  // (7650–7761), are fine.
  EXPECT_TRUE(Load("config_version: 1\nlidar:\n  msop_port: 7910\n  difop_port: 8011\n").ok());
  EXPECT_TRUE(Load("config_version: 1\nipc:\n  domain_id: 1\n").ok());
  EXPECT_FALSE(Load("config_version: 1\nlidar:\n  msop_port: 7400\n").ok());
  EXPECT_TRUE(Load("config_version: 1\nlidar:\n  msop_port: 7512\n").ok());
}

// Keys that nothing read were removed; an old file that has them is refused, each with what
// replaced it (not merely "unknown key").
TEST(ConfigLoader, RemovedKeysAreRefusedNamingTheirReplacement) {
  const LoadedConfig loaded = Load(R"(config_version: 1
estimator:
  extrinsic_imu_lidar:
    estimate_online: true
  window_size: 10
  max_iterations: 5
  num_threads: 1
)");
  ASSERT_EQ(loaded.errors.size(), 4u) << loaded.ErrorReport();
  EXPECT_EQ(loaded.errors[0].ToString(),
            "test.yaml:4:5: estimator.extrinsic_imu_lidar.estimate_online: removed key (it was "
            "never read); use estimator.window.estimate_extrinsic to refine T_imu_lidar in the "
            "window, or estimator.window.calibrate_extrinsic_s to calibrate it in one batch");
  EXPECT_EQ(loaded.errors[1].ToString(),
            "test.yaml:5:3: estimator.window_size: removed key (it was never read); use "
            "estimator.window.window_size instead");
  EXPECT_EQ(loaded.errors[2].key, "estimator.max_iterations");
  EXPECT_THAT(loaded.errors[2].reason, HasSubstr("use estimator.window.max_iterations instead"));
  EXPECT_EQ(loaded.errors[3].key, "estimator.num_threads");
  EXPECT_THAT(loaded.errors[3].reason, HasSubstr("every solve runs on one thread"));
  // Their replacements are read where the messages point.
  const LoadedConfig replaced = Load(R"(config_version: 1
estimator:
  window:
    window_size: 7
    max_iterations: 6
    estimate_extrinsic: true
)");
  ASSERT_TRUE(replaced.ok()) << replaced.ErrorReport();
  EXPECT_EQ(replaced.config.window.window_size, 7u);
  EXPECT_EQ(replaced.config.window.max_iterations, 6);
  EXPECT_TRUE(replaced.config.window.estimate_extrinsic);
  // A removed key is no "did you mean" hint: a typo of one stays a plain unknown key.
  const ConfigError typo = OnlyError(Load("config_version: 1\nestimator:\n  num_thread: 1\n"));
  EXPECT_EQ(typo.reason, "unknown key");
  // Only where it was: estimate_online is unknown in the wheel base's transform.
  const ConfigError elsewhere =
      OnlyError(Load("config_version: 1\nestimator:\n  window:\n    wheel:\n      T_imu_base:\n"
                     "        estimate_online: true\n"));
  EXPECT_EQ(elsewhere.key, "estimator.window.wheel.T_imu_base.estimate_online");
  EXPECT_EQ(elsewhere.reason, "unknown key");
}

TEST(ConfigLoader, DuplicateKeyIsAnError) {
  const LoadedConfig loaded = Load("config_version: 1\nimu:\n  baud: 9600\n  baud: 115200\n");
  ASSERT_FALSE(loaded.ok());
  EXPECT_EQ(loaded.errors[0].key, "imu.baud");
  EXPECT_EQ(loaded.errors[0].line, 4);
  EXPECT_THAT(loaded.errors[0].reason, HasSubstr("duplicate"));
}

TEST(ConfigLoader, SyntaxErrorGivesLine) {
  const ConfigError e = OnlyError(Load("config_version: 1\nlidar:\n  msop_port: [1, 2\n"));
  EXPECT_GT(e.line, 0);
  EXPECT_THAT(e.reason, HasSubstr("YAML syntax error"));
}

TEST(ConfigLoader, NonMappingTopLevelAndMissingFile) {
  EXPECT_THAT(OnlyError(Load("- a\n- b\n")).reason, HasSubstr("expected a mapping"));
  EXPECT_THAT(OnlyError(Load("")).reason, HasSubstr("expected a mapping"));
  const LoadedConfig missing = LoadConfigFile("/nonexistent/swlio.yaml");
  EXPECT_THAT(OnlyError(missing).ToString(),
              HasSubstr("/nonexistent/swlio.yaml: cannot open the configuration file"));
}

TEST(ConfigLoader, NullValueIsAnError) {
  const ConfigError e = OnlyError(Load("config_version: 1\nimu:\n  device:\n"));
  EXPECT_EQ(e.key, "imu.device");
  EXPECT_THAT(e.reason, HasSubstr("got nothing"));
}

TEST(CheckConfigCommand, BrokenConfigPrintsKeyAndLine) {
  const auto dir = test::MakeTempDir("checkcfg");
  const auto file = dir / "broken.yaml";
  std::ofstream(file) << "config_version: 1\nlidar:\n  max_range_m: -1\n";
  const std::string cmd =
      ::swlio::test::ToolPath("swliod").string() + " --check-config " + file.string() + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buf[512];
  while (fgets(buf, sizeof buf, pipe) != nullptr) output += buf;
  const int status = pclose(pipe);
  EXPECT_NE(status, 0);
  EXPECT_THAT(output, HasSubstr("broken.yaml:3:3: lidar.max_range_m: must be in [1, 300], got -1"));
}

}  // namespace
}  // namespace swlio::daemon
