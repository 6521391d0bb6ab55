// The simulator's manifest.yaml: the facts other programs read are exact (clock offsets, the
// true extrinsic, the lens offset) and path_length_m is the length driven in duration_s.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/lie.h"
#include "swlio/drivers/recording_format.h"

namespace swlio::sim {
namespace {

/// The first number after `key` (a regex) in `text`, parsed as the readers do (strtod).
double NumberAfter(const std::string& text, const std::string& key) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(text, m, std::regex(key + R"(\s*([-+0-9.eE]+))"))) << key;
  return m.empty() ? std::nan("") : std::strtod(m[1].str().c_str(), nullptr);
}

std::string Manifest(const SimSetup& setup) {
  return ManifestYaml(setup, RecordingStats{}, 1'000'000'000, "file");
}

// Issue 32: "%.10g" wrote a LiDAR clock offset of 1700081385.407 s as 1700081385.
TEST(SimManifest, ClockOffsetsAndTheExtrinsicAreExact) {
  auto setup = MakeSimSetup("short", 1, 5.0);
  ASSERT_TRUE(setup);
  setup->lidar.clock.offset_s = 1700081385.407;  // the issue's example
  const std::string y = Manifest(*setup);
  EXPECT_EQ(NumberAfter(y, "\nformat_version:"),
            static_cast<double>(drivers::kRecordingFormatVersion));
  EXPECT_EQ(NumberAfter(y, "\nlidar:[\\s\\S]*?clock: \\{offset_s:"), 1700081385.407);
  EXPECT_EQ(NumberAfter(y, "\nlidar:[\\s\\S]*?drift_ppm:"), setup->lidar.clock.drift_ppm);
  EXPECT_EQ(NumberAfter(y, "\nimu:[\\s\\S]*?clock: \\{offset_s:"), setup->imu.clock.offset_s);
  EXPECT_EQ(NumberAfter(y, "\nimu:[\\s\\S]*?drift_ppm:"), setup->imu.clock.drift_ppm);
  EXPECT_EQ(NumberAfter(y, "lens_offset_m:"), 0.03825);
  const Eigen::Isometry3d& T = setup->lidar.T_imu_lidar;
  EXPECT_EQ(NumberAfter(y, "translation_m: \\["), T.translation().x());
  EXPECT_EQ(NumberAfter(y, "translation_m: \\[[^,]*,"), T.translation().y());
  const Eigen::Quaterniond q = lie::PositiveW(Eigen::Quaterniond(T.linear()));
  EXPECT_EQ(NumberAfter(y, "quaternion_xyzw: \\["), q.x());
  EXPECT_EQ(NumberAfter(y, "quaternion_xyzw: \\[[^,]*,[^,]*,[^,]*,"), q.w());
  // The LiDAR is mounted forward now (the drivers' frame), about 1° off identity.
  EXPECT_LT(Eigen::AngleAxisd(T.linear()).angle(), 5.0 * 3.14159265358979 / 180.0);
}

// With --duration the manifest gives the part driven, not the whole route; the reference is
// the horizontal path of the true trajectory summed over 1 ms steps.
TEST(SimManifest, PathLengthIsWhatWasDrivenInTheDuration) {
  auto cut = MakeSimSetup("short", 1, 12.0);
  auto whole = MakeSimSetup("short", 1);
  ASSERT_TRUE(cut && whole);
  double driven_m = 0.0;
  Eigen::Vector3d previous = cut->trajectory->At(0.0).p_world;
  for (int i = 1; i <= 12'000; ++i) {
    const Eigen::Vector3d p = cut->trajectory->At(i * 1e-3).p_world;
    driven_m += (p - previous).head<2>().norm();
    previous = p;
  }
  const double cut_m = NumberAfter(Manifest(*cut), "\npath_length_m:");
  EXPECT_NEAR(cut_m, driven_m, 0.01);
  EXPECT_GT(driven_m, 3.0);
  const double whole_m = NumberAfter(Manifest(*whole), "\npath_length_m:");
  EXPECT_NEAR(whole_m, whole->trajectory->length_m(), 1e-9);
  EXPECT_LT(cut_m, 0.5 * whole_m);
}

}  // namespace
}  // namespace swlio::sim
