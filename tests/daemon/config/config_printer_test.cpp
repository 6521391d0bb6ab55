// PrintConfig (swliod --print-config) against the loader: what it prints loads back into the
// same configuration, to the last bit, and holds every key of the shipped file.

#include "swlio/daemon/config/config_printer.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "swlio/daemon/config/config_loader.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Loads `printed` (from elsewhere: no relative path may be left in it) or fails the test.
DaemonConfig LoadPrinted(const std::string& printed) {
  const LoadedConfig loaded = LoadConfigText(printed, "printed.yaml", "/nonexistent/elsewhere");
  EXPECT_TRUE(loaded.ok()) << loaded.ErrorReport() << "\n" << printed;
  return loaded.config;
}

/// Dotted paths of the block-mapping keys in `yaml` (indentation decides the nesting;
/// comments, list items and flow collections are skipped).
std::set<std::string> KeyPaths(const std::string& yaml) {
  static const std::regex kKey(R"(^( *)([A-Za-z_][A-Za-z0-9_]*):.*)");
  std::set<std::string> paths;
  std::vector<std::pair<size_t, std::string>> parents;  // indent, path
  std::istringstream lines(yaml);
  std::string line;
  std::smatch m;
  while (std::getline(lines, line)) {
    if (!std::regex_match(line, m, kKey)) continue;
    const size_t indent = m[1].length();
    while (!parents.empty() && parents.back().first >= indent) parents.pop_back();
    const std::string path =
        parents.empty() ? m[2].str() : parents.back().second + "." + m[2].str();
    paths.insert(path);
    parents.emplace_back(indent, path);
  }
  return paths;
}

TEST(ConfigPrinter, ShippedConfigPrintsAndLoadsBackTheSame) {
  const LoadedConfig shipped = LoadConfigFile(test::SourceDir() / "config" / "swlio.yaml");
  ASSERT_TRUE(shipped.ok()) << shipped.ErrorReport();
  const std::string printed = PrintConfig(shipped.config);
  const DaemonConfig again = LoadPrinted(printed);
  EXPECT_EQ(PrintConfig(again), printed);
  // The DDS XML named relative to the file is printed absolute, so it is found from anywhere.
  EXPECT_EQ(again.ipc.dds_config_file, shipped.config.ipc.dds_config_file);
  EXPECT_TRUE(std::filesystem::path(again.ipc.dds_config_file).is_absolute());
  EXPECT_THAT(printed, HasSubstr("dds_config_file: " + shipped.config.ipc.dds_config_file));
  // Numbers as the shipped file states them, exactly.
  EXPECT_EQ(again.estimator.imu_noise.gyro_noise_density_radps_per_sqrthz,
            shipped.config.estimator.imu_noise.gyro_noise_density_radps_per_sqrthz);
  EXPECT_EQ(again.window.bootstrap.initializer.rotation_sigma_rad,
            shipped.config.window.bootstrap.initializer.rotation_sigma_rad);
  EXPECT_THAT(printed, HasSubstr("  rotation_sigma_rad: 0.003490658503988659\n"));
  EXPECT_THAT(printed, HasSubstr("  cut_angle_deg: 0.0\n"));
  EXPECT_THAT(printed, HasSubstr("  rcvbuf_bytes: 8388608\n"));
  EXPECT_THAT(printed, HasSubstr("  rx_batch_ms: 5\n"));
  EXPECT_THAT(printed, HasSubstr("  stamp_clock: realtime\n"));
  EXPECT_THAT(printed, HasSubstr("  lens_offset_m: 0.03825\n"));  // RS16: rs_driver's RX
  EXPECT_THAT(printed, HasSubstr("  - {name: lidar_rx, priority: 80, cpu: -1, nice: -10}\n"));
}

TEST(ConfigPrinter, MinimalConfigPrintsEveryDefault) {
  const LoadedConfig minimal = LoadConfigText("config_version: 1\n", "min.yaml", "/etc/swlio");
  ASSERT_TRUE(minimal.ok()) << minimal.ErrorReport();
  const std::string printed = PrintConfig(minimal.config);
  EXPECT_EQ(PrintConfig(LoadPrinted(printed)), printed);
  // The struct defaults, but for the DDS XML's path, resolved against the file's directory.
  DaemonConfig defaults;
  defaults.ipc.dds_config_file = "/etc/swlio/cyclonedds-loopback.xml";
  EXPECT_EQ(printed, PrintConfig(defaults));
  EXPECT_THAT(printed, HasSubstr("dds_config_file: /etc/swlio/cyclonedds-loopback.xml\n"));
  EXPECT_THAT(printed, HasSubstr("    window_size: 5\n"));
  EXPECT_THAT(printed, HasSubstr("  signals: []\n"));
  EXPECT_THAT(printed, HasSubstr("    - {name: imu_rx, priority: 80, cpu: -1, nice: -10}\n"));
  EXPECT_THAT(printed, HasSubstr("  save_path: \"\"\n"));
  // The GNSS origin is absent by default: not a key to print, and said so.
  EXPECT_THAT(printed, Not(HasSubstr("origin_lat_deg:")));
  EXPECT_THAT(printed, HasSubstr("origin_lat_deg, _lon_deg, _height_m absent"));
}

// Every key the shipped file shows is printed, and nothing else: the example CAN signals (a
// commented-out list there) print as an empty list, the lens offset (commented out there: the
// model's vendor value) as that value.
TEST(ConfigPrinter, PrintsTheShippedFilesKeys) {
  const auto path = test::SourceDir() / "config" / "swlio.yaml";
  const LoadedConfig shipped = LoadConfigFile(path);
  ASSERT_TRUE(shipped.ok()) << shipped.ErrorReport();
  std::set<std::string> want = KeyPaths(ReadFile(path));
  ASSERT_GT(want.size(), 200u);
  ASSERT_TRUE(want.count("estimator.window.bootstrap.initializer.gravity_iterations"));
  want.insert("can.signals");
  want.insert("lidar.lens_offset_m");
  EXPECT_EQ(KeyPaths(PrintConfig(shipped.config)), want);
}

// Values away from the defaults, of every kind the loader reads: numbers that are not short in
// binary, hexadecimal CAN identifiers, a start bit and a byte offset, angles, a GNSS origin,
// paths relative to the file, scheduling entries.
TEST(ConfigPrinter, ValuesOfEveryKindRoundTripExactly) {
  const LoadedConfig original = LoadConfigText(R"(config_version: 1
lidar:
  cut_angle_deg: 0.1
  vertical_angles_deg: [-15.1, -13, -11, -9, -7, -5, -3, -1, 1, 3, 5, 7, 9, 11, 13, 15.000000000000002]
  max_range_m: 1.0e2
can:
  enabled: true
  mode: wheel_speeds
  track_width_m: 0.30000000000000004
  signals:
    - {role: left_wheel_speed, can_id: 0x1ABCDEF, extended: true, start_bit: 7, length_bits: 16,
       byte_order: motorola, signed: false, scale: -0.001, offset: 0.25, dlc: 8}
    - {role: right_wheel_speed, can_id: 0x201, byte_offset: 2, length_bits: 16, scale: 1e-3}
estimator:
  extrinsic_imu_lidar:
    translation_m: [0.1, -0.02, 0.3]
    rotation_rpy_deg: [0.3, -1.7, 179.9]
  window:
    window_size: 7
    wheel:
      enabled: true
      T_imu_base:
        translation_m: [-0.4, 0.1, -0.3]
        rotation_rpy_deg: [1.5, -2.25, 90.1]
  loop_closure:
    gnss:
      enabled: true
      origin_lat_deg: 31.123456789012345
      origin_lon_deg: 121.5
      origin_height_m: -3.0
      antenna_imu_m: [0.2, 0.0, 0.7]
map:
  save_path: maps/yard.swlmap
ipc:
  dds_config_file: ../xml/dds.xml
logging:
  directory: logs
realtime:
  threads:
    - {name: lidar_rx, priority: 80, cpu: 1, nice: -10}
    - {name: optimizer, priority: 0, cpu: -1, nice: 5}
)",
                                               "odd.yaml", "/etc/swlio/site");
  ASSERT_TRUE(original.ok()) << original.ErrorReport();
  const DaemonConfig& a = original.config;
  const std::string printed = PrintConfig(a);
  const DaemonConfig b = LoadPrinted(printed);
  EXPECT_EQ(PrintConfig(b), printed);

  EXPECT_EQ(b.lidar.cut_angle_deg, 0.1);
  EXPECT_EQ(b.lidar.vertical_angles_deg, a.lidar.vertical_angles_deg);
  EXPECT_EQ(b.lidar.vertical_angles_deg[15], 15.000000000000002);
  EXPECT_EQ(b.lidar.max_range_m, 100.0);
  EXPECT_EQ(b.can.track_width_m, 0.30000000000000004);
  ASSERT_EQ(b.can.signals.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    SCOPED_TRACE(i);
    const drivers::CanSignalConfig& x = a.can.signals[i];
    const drivers::CanSignalConfig& y = b.can.signals[i];
    EXPECT_EQ(y.role, x.role);
    EXPECT_EQ(y.can_id, x.can_id);
    EXPECT_EQ(y.extended, x.extended);
    EXPECT_EQ(y.start_bit, x.start_bit);
    EXPECT_EQ(y.byte_offset, x.byte_offset);
    EXPECT_EQ(y.length_bits, x.length_bits);
    EXPECT_EQ(y.byte_order, x.byte_order);
    EXPECT_EQ(y.is_signed, x.is_signed);
    EXPECT_EQ(y.scale, x.scale);
    EXPECT_EQ(y.offset, x.offset);
    EXPECT_EQ(y.dlc, x.dlc);
  }
  EXPECT_THAT(printed, HasSubstr("can_id: 0x1abcdef"));
  EXPECT_EQ(b.estimator.extrinsic_imu_lidar.rotation_rpy_deg,
            a.estimator.extrinsic_imu_lidar.rotation_rpy_deg);
  EXPECT_EQ(b.estimator.extrinsic_imu_lidar.translation_m,
            a.estimator.extrinsic_imu_lidar.translation_m);
  EXPECT_EQ(b.window.window_size, 7u);
  // The wheel base's numbers as given, so its transform is the same to the last bit.
  EXPECT_EQ(b.window.wheel.T_imu_base.rotation_rpy_deg, (std::array<double, 3>{1.5, -2.25, 90.1}));
  EXPECT_EQ(b.window.wheel.T_imu_base.translation_m, (std::array<double, 3>{-0.4, 0.1, -0.3}));
  EXPECT_TRUE(b.window.wheel.T_imu_base.ToIsometry().matrix() ==
              a.window.wheel.T_imu_base.ToIsometry().matrix());
  EXPECT_EQ(b.loop_closure.gnss.origin_lat_deg, 31.123456789012345);
  EXPECT_EQ(b.loop_closure.gnss.origin_height_m, -3.0);
  EXPECT_EQ(b.loop_closure.gnss.antenna_imu_m, a.loop_closure.gnss.antenna_imu_m);
  // Relative paths were resolved against the file's directory and are printed so.
  EXPECT_EQ(b.map.save_path, "/etc/swlio/site/maps/yard.swlmap");
  EXPECT_EQ(b.ipc.dds_config_file, "/etc/swlio/xml/dds.xml");
  EXPECT_EQ(b.logging.directory, "/etc/swlio/site/logs");
  ASSERT_EQ(b.realtime.threads.size(), 2u);
  EXPECT_EQ(b.realtime.threads[0].cpu, 1);
  EXPECT_EQ(b.realtime.threads[1].nice, 5);
}

// A removed key is neither printed nor taken back.
TEST(ConfigPrinter, PrintsNoRemovedKey) {
  const std::string printed = PrintConfig(DaemonConfig{});
  for (const char* removed : {"estimate_online", "num_threads"}) {
    EXPECT_THAT(printed, Not(HasSubstr(removed)));
  }
  const std::set<std::string> keys = KeyPaths(printed);
  EXPECT_EQ(keys.count("estimator.window_size"), 0u);
  EXPECT_EQ(keys.count("estimator.max_iterations"), 0u);
  EXPECT_EQ(keys.count("estimator.window.window_size"), 1u);
}

}  // namespace
}  // namespace swlio::daemon
