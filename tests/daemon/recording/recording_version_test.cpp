// A recording made before issue 32 (manifest format_version 1: LiDAR frame of the RoboSense
// manual, no lens offset in the simulator) is refused with what to do, never read in the wrong
// frame; the extrinsic the refusal proposes for a swliod recording (R·Rz(+90°)) maps the new
// decoder's points where the old extrinsic mapped the manual frame's.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <regex>
#include <sstream>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/lie.h"
#include "swlio/daemon/recording/recorder.h"
#include "swlio/daemon/recording/recording_reader.h"
#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/rs16_encoder.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void SetFormatVersion(const std::filesystem::path& dir, int version) {
  const std::string text = ReadText(dir / "manifest.yaml");
  const std::string changed =
      std::regex_replace(text, std::regex("\nformat_version: [0-9]+\n"),
                         "\nformat_version: " + std::to_string(version) + "\n");
  ASSERT_NE(changed, text);
  std::ofstream(dir / "manifest.yaml") << changed;
}

TEST(RecordingVersion, TodaysRecordingIsReadAndAnOldOneRefused) {
  const auto dir = test::MakeTempDir("rec_version");
  const auto setup = sim::MakeSimSetup("short", 3, 2.0);
  ASSERT_TRUE(setup);
  sim::RecordingStats stats;
  std::string error;
  ASSERT_TRUE(sim::WriteRecording(*setup, dir, &stats, &error)) << error;
  EXPECT_EQ(ManifestVersionProblem(dir), "");
  EXPECT_NE(RecordingReader::Open(dir, {}, {}, &error), nullptr) << error;

  SetFormatVersion(dir, 1);
  EXPECT_EQ(RecordingReader::Open(dir, {}, {}, &error), nullptr);
  EXPECT_NE(error.find("format_version 1"), std::string::npos) << error;
  EXPECT_NE(error.find("RoboSense manual's frame"), std::string::npos) << error;
  EXPECT_NE(error.find("swlio-sim"), std::string::npos) << error;

  SetFormatVersion(dir, 3);
  EXPECT_EQ(RecordingReader::Open(dir, {}, {}, &error), nullptr);
  EXPECT_NE(error.find("newer swlio"), std::string::npos) << error;

  std::filesystem::remove(dir / "manifest.yaml");
  EXPECT_EQ(RecordingReader::Open(dir, {}, {}, &error), nullptr);
  EXPECT_NE(error.find("manifest.yaml"), std::string::npos) << error;
}

// swliod --record writes the current version, and the numbers the readers take back exactly.
TEST(RecordingVersion, RecorderManifestIsCurrentAndExact) {
  const auto dir = test::MakeTempDir("rec_version_recorder");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = lie::QuatFromRpy(0.1, -0.2, 1.0 / 3.0).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.1 / 3.0, -std::sqrt(2.0) / 10.0, 0.123456789012345);
  const TimeScale time{123'456'789'012, 2.0 / 3.0};
  std::string error;
  ASSERT_NE(Recorder::Create(dir, DaemonConfig{}, T, time, &error), nullptr) << error;
  EXPECT_EQ(ManifestVersionProblem(dir), "");
  const TimeScale read_time = ManifestTimeScale(dir);
  EXPECT_EQ(read_time.scale, time.scale);
  EXPECT_EQ(read_time.origin_ns, time.origin_ns);
  const std::optional<Eigen::Isometry3d> read_T = ManifestExtrinsic(dir);
  ASSERT_TRUE(read_T);
  EXPECT_EQ(read_T->translation(), T.translation());
  EXPECT_LT((read_T->linear() - T.linear()).norm(), 1e-15);
  EXPECT_NE(ReadText(dir / "manifest.yaml").find("lens_offset_m: 0.03825\n"), std::string::npos);
}

/// A version-1 swliod manifest with this extrinsic (what the old recorder wrote).
std::filesystem::path OldDaemonRecording(const Eigen::Quaterniond& q) {
  const auto dir = test::MakeTempDir("rec_version_daemon");
  char line[256];
  std::snprintf(line, sizeof line, "  quaternion_xyzw: [%.12g, %.12g, %.12g, %.12g]\n", q.x(),
                q.y(), q.z(), q.w());
  std::ofstream(dir / "manifest.yaml")
      << "# swliod recording\nformat_version: 1\nmode: daemon\nextrinsic_T_imu_lidar:\n"
      << "  translation_m: [0.1, 0.2, -0.3]\n"
      << line << "lidar:\n  model: rs16\n";
  return dir;
}

Eigen::Quaterniond ProposedQuaternion(const std::string& message) {
  std::smatch m;
  const std::regex number("(-?[0-9.e+-]+)");
  const std::regex list(R"(quaternion_xyzw: \[([^\]]*)\])");
  EXPECT_TRUE(std::regex_search(message, m, list)) << message;
  double v[4] = {0, 0, 0, 1};
  std::stringstream s(m[1].str());
  char comma = 0;
  s >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3];
  return Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
}

// The manual's formula (RS-LiDAR-16 User Manual §8.1), written here: x = r cos ω sin α,
// y = r cos ω cos α, z = r sin ω.
Eigen::Vector3d ManualPoint(double range_m, double omega_deg, double alpha_deg) {
  const double w = omega_deg * kDeg, a = alpha_deg * kDeg;
  return range_m *
         Eigen::Vector3d(std::cos(w) * std::sin(a), std::cos(w) * std::cos(a), std::sin(w));
}

// The migration note's sign, checked against the decoder rather than trusted: old extrinsic ·
// manual-frame point = proposed extrinsic · decoded point, for every slot of a packet, and the
// opposite sign (Rz(−90°)) does not do it.
TEST(RecordingVersion, ProposedExtrinsicMapsTheNewFrameAsTheOldOneMappedTheManualsFrame) {
  const Eigen::Quaterniond q_old = lie::QuatFromRpy(3 * kDeg, -2 * kDeg, -88 * kDeg);
  const std::string problem = ManifestVersionProblem(OldDaemonRecording(q_old));
  ASSERT_NE(problem.find("R·Rz(+90°)"), std::string::npos) << problem;
  const Eigen::Matrix3d R_new = ProposedQuaternion(problem).normalized().toRotationMatrix();
  const Eigen::Matrix3d R_old = q_old.toRotationMatrix();
  const Eigen::Matrix3d R_wrong = R_old * Eigen::AngleAxisd(-90 * kDeg, Eigen::Vector3d::UnitZ());

  drivers::LidarConfig config;
  config.min_range_m = 0.0;
  drivers::Rs16DecoderOptions no_lens;  // the manual's formula has no lens term
  no_lens.lens_offset_m = 0.0;
  const drivers::Rs16Decoder decoder(config, no_lens);
  drivers::Rs16MsopContent content;
  content.t_sensor_ns = 1'700'000'000'000'000'000;
  for (size_t b = 0; b < 12; ++b) {
    content.blocks[b].azimuth_deg = 37.0 * static_cast<double>(b);  // all around
    for (size_t s = 0; s < 32; ++s) {
      content.blocks[b].range_m[s] = 2.0f + 0.5f * static_cast<float>(s);
    }
  }
  std::vector<uint8_t> packet(1248);
  ASSERT_TRUE(drivers::EncodeRs16Msop(content, packet));
  drivers::LidarPacketDecoder::ReturnBuffer buffer;
  drivers::LidarPacketSummary summary;
  ASSERT_EQ(decoder.DecodeData(packet, buffer, &summary), drivers::DecodeStatus::kOk);
  ASSERT_EQ(summary.returns, 384u);
  for (uint32_t i = 0; i < summary.returns; ++i) {
    const drivers::LidarReturn& r = buffer[i];
    const double omega = decoder.vertical_deg_by_channel()[r.slot % 16];
    const Eigen::Vector3d p_manual = ManualPoint(r.range_m, omega, r.azimuth_deg);
    const Eigen::Vector3d p_new(r.x_m, r.y_m, r.z_m);
    EXPECT_LT((R_new * p_new - R_old * p_manual).norm(), 1e-4) << "slot " << r.slot;
    EXPECT_GT((R_wrong * p_new - R_old * p_manual).norm(), 1.0) << "slot " << r.slot;
  }
}

}  // namespace
}  // namespace swlio::daemon
