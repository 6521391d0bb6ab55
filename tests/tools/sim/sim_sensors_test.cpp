// The simulator's sensor streams against its own ground truth, through the real drivers.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"
#include "test_data.h"

namespace swlio::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

SimSetup MakeSetupOrDie(const std::string& name, uint64_t seed, double duration_s) {
  auto s = MakeSimSetup(name, seed, duration_s);
  EXPECT_TRUE(s.has_value());
  return std::move(*s);
}

/// Decoded MSOP returns equal the ray-cast truth within the wire format's quantization:
/// 5 mm in range (rounded) and 0.01° per block azimuth, which the decoder's interpolation
/// between two quantized block azimuths (extrapolation for the last block) can double;
/// times within 1 µs (header resolution).
TEST(SimLidar, PacketsDecodeBackToTheRayCastPoints) {
  const SimSetup setup = MakeSetupOrDie("aggressive", 4, 8.0);
  LidarSimulator lidar(setup.world.get(), setup.trajectory.get(), setup.lidar, 4);
  drivers::Rs16Decoder decoder{drivers::LidarConfig{}};
  drivers::LidarPacketDecoder::ReturnBuffer buffer;
  SimPacket packet;
  std::vector<SimReturn> truth;
  size_t checked = 0, packets = 0;
  while (lidar.Next(&packet, &truth) && packets < 500) {
    if (decoder.Classify(packet.bytes) == drivers::LidarPacketKind::kInfo) {
      ASSERT_EQ(decoder.DecodeInfo(packet.bytes), drivers::DecodeStatus::kOk);
      continue;
    }
    drivers::LidarPacketSummary summary;
    ASSERT_EQ(decoder.DecodeData(packet.bytes, buffer, &summary), drivers::DecodeStatus::kOk);
    ++packets;
    for (uint32_t i = 0; i < summary.returns; ++i) {
      const drivers::LidarReturn& r = buffer[i];
      const SimReturn& t = truth[r.slot];
      ASSERT_GT(t.range_m, 0.0);
      const double az = (setup.lidar.initial_azimuth_deg +
                         360.0 * setup.lidar.rpm / 60.0 * NsToSec(t.t_true_ns)) *
                        kDeg;
      const double om = setup.lidar.vertical_angles_deg[t.channel] * kDeg;
      // rs_driver's formula: lens centre 3.825 cm out along the azimuth, x forward, y left.
      const Eigen::Vector3d expected =
          0.03825 * Eigen::Vector3d(std::cos(az), -std::sin(az), 0.0) +
          t.range_m * Eigen::Vector3d(std::cos(om) * std::cos(az), -std::cos(om) * std::sin(az),
                                      std::sin(om));
      const Eigen::Vector3d got(r.x_m, r.y_m, r.z_m);
      EXPECT_LT((got - expected).norm(), 0.0026 + t.range_m * 0.021 * kDeg) << "slot " << r.slot;
      const double t_sensor_s = setup.lidar.clock.ToDevice(NsToSec(t.t_true_ns));
      EXPECT_NEAR(NsToSec(r.t_sensor_ns), t_sensor_s, 1.5e-6);
      ++checked;
    }
    size_t valid = 0;
    for (const SimReturn& t : truth) valid += t.range_m > 0.0 ? 1 : 0;
    EXPECT_EQ(valid, summary.returns);
  }
  EXPECT_GT(checked, 50'000u);
}

/// Without range noise, a decoded return taken into the world with the LiDAR's true pose at its
/// firing lies on the surface the simulator's ray hit: rays start at the lens centre the decoder
/// adds, in the decoder's frame, and the extrinsic maps that frame.
TEST(SimLidar, DecodedReturnsLieOnTheSurfacesHit) {
  SimSetup setup = MakeSetupOrDie("aggressive", 5, 8.0);
  setup.lidar.range_sigma_m = 0.0;
  LidarSimulator lidar(setup.world.get(), setup.trajectory.get(), setup.lidar, 5);
  drivers::Rs16Decoder decoder{drivers::LidarConfig{}};
  drivers::LidarPacketDecoder::ReturnBuffer buffer;
  SimPacket packet;
  std::vector<SimReturn> truth;
  size_t checked = 0;
  double worst_m = 0.0;
  for (size_t packets = 0; lidar.Next(&packet, &truth) && packets < 300;) {
    if (decoder.Classify(packet.bytes) == drivers::LidarPacketKind::kInfo) {
      ASSERT_EQ(decoder.DecodeInfo(packet.bytes), drivers::DecodeStatus::kOk);
      continue;
    }
    drivers::LidarPacketSummary summary;
    ASSERT_EQ(decoder.DecodeData(packet.bytes, buffer, &summary), drivers::DecodeStatus::kOk);
    ++packets;
    for (uint32_t i = 0; i < summary.returns; ++i) {
      const drivers::LidarReturn& r = buffer[i];
      const SimReturn& t = truth[r.slot];
      const Kinematics k = setup.trajectory->At(NsToSec(t.t_true_ns));
      Eigen::Isometry3d T_world_imu = Eigen::Isometry3d::Identity();
      T_world_imu.linear() = k.R_world_body;
      T_world_imu.translation() = k.p_world;
      const Eigen::Vector3d p_world =
          T_world_imu * setup.lidar.T_imu_lidar * Eigen::Vector3d(r.x_m, r.y_m, r.z_m);
      const double err = (p_world - t.p_world).norm();
      worst_m = std::max(worst_m, err);
      EXPECT_LT(err, 0.0026 + t.range_m * 0.021 * kDeg) << "slot " << r.slot;
      ++checked;
    }
  }
  RecordProperty("worst_um", static_cast<int>(worst_m * 1e6));
  EXPECT_GT(checked, 30'000u);
}

/// `SimPacket::t_header_s` is what the header time stands for: an MSOP's first firing, a
/// DIFOP's whole second; the header holds it on the sensor clock (to the µs it carries).
TEST(SimLidar, HeaderSimTimeIsTheTimeInTheHeader) {
  const SimSetup setup = MakeSetupOrDie("short", 3, 3.0);
  LidarSimulator lidar(setup.world.get(), setup.trajectory.get(), setup.lidar, 3);
  SimPacket packet;
  std::vector<SimReturn> truth;
  size_t msop = 0, difop = 0;
  while (lidar.Next(&packet, &truth)) {
    const bool is_difop = packet.dst_port == setup.lidar.difop_port;
    namespace rs16 = drivers::rs16;
    int64_t t_header_ns = 0;
    ASSERT_TRUE(
        rs16::ParseTime(packet.bytes.data() + (is_difop ? rs16::kDifopTime : rs16::kTimeOffset),
                        rs16::TimeFormat::kYmd, &t_header_ns));
    const double t_device_s = setup.lidar.clock.ToDevice(packet.t_header_s);
    EXPECT_NEAR(static_cast<double>(t_header_ns - SecToNs(t_device_s)) * 1e-9, 0.0, 1.5e-6);
    if (is_difop) {
      EXPECT_EQ(packet.t_header_s, static_cast<double>(difop++));
    } else {
      EXPECT_NEAR(packet.t_header_s, NsToSec(static_cast<int64_t>(msop++) * kMsopPeriodNs), 1e-12);
      EXPECT_EQ(SecToNs(packet.t_header_s), truth[0].t_true_ns);
    }
  }
  EXPECT_GT(msop, 2000u);
  EXPECT_EQ(difop, 3u);  // seconds 0, 1, 2: none at 3.0 s, after the last MSOP
}

/// The noise-free ray-cast hit lies on the world surface it reports, seen from the LiDAR pose
/// at the firing's own time (motion during the sweep is simulated).
TEST(SimLidar, HitsAreSeenFromThePoseAtTheirOwnTime) {
  const SimSetup setup = MakeSetupOrDie("aggressive", 2, 6.0);
  LidarSimulator lidar(setup.world.get(), setup.trajectory.get(), setup.lidar, 2);
  SimPacket packet;
  std::vector<SimReturn> truth;
  size_t ground = 0;
  for (int p = 0; p < 800 && lidar.Next(&packet, &truth); ++p) {
    for (const SimReturn& t : truth) {
      if (t.true_range_m <= 0.0) continue;
      const Kinematics k = setup.trajectory->At(NsToSec(t.t_true_ns));
      Eigen::Isometry3d T_world_imu = Eigen::Isometry3d::Identity();
      T_world_imu.linear() = k.R_world_body;
      T_world_imu.translation() = k.p_world;
      // Ranges start at the lens centre, 3.825 cm out along the firing azimuth.
      const double az = (setup.lidar.initial_azimuth_deg +
                         360.0 * setup.lidar.rpm / 60.0 * NsToSec(t.t_true_ns)) *
                        kDeg;
      const Eigen::Vector3d lens =
          T_world_imu * setup.lidar.T_imu_lidar *
          Eigen::Vector3d(0.03825 * std::cos(az), -0.03825 * std::sin(az), 0.0);
      EXPECT_NEAR((t.p_world - lens).norm(), t.true_range_m, 1e-3);
      if (t.cls == SurfaceClass::kGround) {
        EXPECT_NEAR(t.p_world.z(), setup.world->terrain.SurfaceHeight(t.p_world.head<2>()), 1e-3);
        ++ground;
      }
    }
  }
  EXPECT_GT(ground, 3'000u);
}

/// Strapdown integration of 1 s of simulated IMU samples (true biases removed) reproduces the
/// true change of attitude and velocity within 3σ of the white noise (plus a small allowance
/// for the 400 Hz integration itself).
TEST(SimImu, OneSecondOfSamplesMatchesTheTrueMotion) {
  const SimSetup setup = MakeSetupOrDie("aggressive", 3, 40.0);
  const std::vector<SimImuSample> imu = SimulateImu(*setup.trajectory, setup.imu, 3);
  const double dt = 1.0 / setup.imu.rate_hz;
  const double sigma_rot = setup.imu.noise.gyro_noise_density * std::sqrt(1.0);
  const double sigma_vel = setup.imu.noise.acc_noise_density * std::sqrt(1.0) +
                           setup.imu.gravity_mps2 * sigma_rot;  // tilt error couples gravity
  const Eigen::Vector3d g(0.0, 0.0, -setup.imu.gravity_mps2);
  for (const double t_start : {5.0, 12.0, 20.0, 31.0}) {
    size_t i = 0;
    while (NsToSec(imu[i].t_true_ns) < t_start) ++i;
    const Kinematics k0 = setup.trajectory->At(NsToSec(imu[i].t_true_ns));
    Eigen::Matrix3d R = k0.R_world_body;
    Eigen::Vector3d v = k0.v_world;
    const size_t n = static_cast<size_t>(setup.imu.rate_hz);
    for (size_t j = i; j < i + n; ++j) {  // midpoint rule between consecutive samples
      const Eigen::Vector3d w =
          0.5 * (imu[j].gyro_radps + imu[j + 1].gyro_radps) - imu[j].bias_gyro;
      const Eigen::Vector3d f = 0.5 * (imu[j].acc_mps2 + imu[j + 1].acc_mps2) - imu[j].bias_acc;
      const Eigen::Matrix3d R_mid = R * lie::Exp(0.5 * w * dt);
      v += (R_mid * f + g) * dt;
      R = R * lie::Exp(w * dt);
    }
    const Kinematics k1 = setup.trajectory->At(NsToSec(imu[i + n].t_true_ns));
    EXPECT_LT(lie::Log(k1.R_world_body.transpose() * R).norm(),
              3.0 * sigma_rot * std::sqrt(3.0) + 2e-4)
        << "t=" << t_start;
    EXPECT_LT((v - k1.v_world).norm(), 3.0 * sigma_vel * std::sqrt(3.0) + 2e-3) << "t=" << t_start;
  }
}

/// Device clock and delivery: SampleTimeFine follows offset and drift; receive times come in
/// bursts after the sample and never run backwards.
TEST(SimImu, DeviceClockAndSerialBursts) {
  const SimSetup setup = MakeSetupOrDie("short", 5, 20.0);
  const std::vector<SimImuSample> imu = SimulateImu(*setup.trajectory, setup.imu, 5);
  ASSERT_GT(imu.size(), 7000u);
  size_t bursts = 0;
  for (size_t i = 1; i < imu.size(); ++i) {
    const double device_s = setup.imu.clock.ToDevice(NsToSec(imu[i].t_true_ns));
    EXPECT_NEAR(imu[i].sample_time_fine * 1e-4, std::fmod(device_s, 429496.7296), 1e-4);
    EXPECT_EQ(static_cast<uint16_t>(imu[i - 1].packet_counter + 1), imu[i].packet_counter);
    EXPECT_GE(imu[i].t_rx_ns, imu[i].t_true_ns);
    EXPECT_GE(imu[i].t_rx_ns, imu[i - 1].t_rx_ns);
    bursts += imu[i].t_rx_ns != imu[i - 1].t_rx_ns ? 1 : 0;
  }
  EXPECT_LT(bursts * 3, imu.size() * 2) << "frames arrive in bursts, not one by one";
}

/// Firing times in the decoded packets advance by the RS16 schedule: 2.8 µs between lasers,
/// 55.5 µs between firing sequences (checked on the sensor clock, drift removed).
TEST(SimLidar, PerPointTimesFollowTheFiringSchedule) {
  const SimSetup setup = MakeSetupOrDie("short", 6, 3.0);
  LidarSimulator lidar(setup.world.get(), setup.trajectory.get(), setup.lidar, 6);
  SimPacket packet;
  std::vector<SimReturn> truth;
  while (lidar.Next(&packet, &truth) && truth.empty()) {
  }
  ASSERT_EQ(truth.size(), 384u);
  for (size_t k = 0; k < truth.size(); ++k) {
    const int64_t expected = truth[0].t_true_ns + static_cast<int64_t>(k / 16) * 55'500 +
                             static_cast<int64_t>(k % 16) * 2'800;
    EXPECT_NEAR(static_cast<double>(truth[k].t_true_ns), static_cast<double>(expected), 1.0);
  }
}

std::string ReadAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SimRecording, SameNameAndSeedGiveIdenticalBytes) {
  const auto a = test::MakeTempDir("sim_a"), b = test::MakeTempDir("sim_b");
  RecordingStats stats;
  std::string error;
  ASSERT_TRUE(WriteRecording(MakeSetupOrDie("degenerate", 9, 2.5), a, &stats, &error)) << error;
  ASSERT_TRUE(WriteRecording(MakeSetupOrDie("degenerate", 9, 2.5), b, &stats, &error)) << error;
  for (const char* f :
       {"lidar.pcap", "imu.xbus", "imu.rx.csv", "groundtruth.tum", "manifest.yaml"}) {
    const std::string x = ReadAll(a / f), y = ReadAll(b / f);
    EXPECT_FALSE(x.empty()) << f;
    EXPECT_TRUE(x == y) << f << " differs between two runs";
  }
  const auto c = test::MakeTempDir("sim_c");
  ASSERT_TRUE(WriteRecording(MakeSetupOrDie("degenerate", 10, 2.5), c, &stats, &error)) << error;
  EXPECT_FALSE(ReadAll(a / "lidar.pcap") == ReadAll(c / "lidar.pcap")) << "the seed matters";
  EXPECT_GT(stats.msop_packets, 1800u);
  EXPECT_GT(stats.imu_frames, 900u);
}

TEST(SimImu, FramesDecodeToTheSimulatedSamples) {
  const SimSetup setup = MakeSetupOrDie("short", 7, 3.0);
  const std::vector<SimImuSample> imu = SimulateImu(*setup.trajectory, setup.imu, 7);
  std::array<uint8_t, 512> frame{};
  drivers::xsens::XbusFramer framer;
  for (size_t i = 0; i < 50; ++i) {
    const size_t n = EncodeImuFrame(imu[i], frame);
    ASSERT_GT(n, 0u);
    drivers::xsens::MtData2Sample m;
    ASSERT_EQ(drivers::xsens::DecodeMtData2(std::span(frame).subspan(4, n - 5), &m),
              drivers::xsens::MtData2Status::kOk);
    EXPECT_EQ(*m.sample_time_fine, imu[i].sample_time_fine);
    EXPECT_EQ(*m.packet_counter, imu[i].packet_counter);
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR((*m.acc_mps2)[static_cast<size_t>(a)], imu[i].acc_mps2(a), 1e-5);
      EXPECT_NEAR((*m.rate_of_turn_radps)[static_cast<size_t>(a)], imu[i].gyro_radps(a), 1e-6);
    }
  }
}

}  // namespace
}  // namespace swlio::sim
