// The simulator's GNSS: GnssPvtData items in the IMU's Xbus frames, decoded by the drivers and
// converted back to the local ENU frame, against the true antenna position; the error model,
// the faults, and the longer frames' later arrival.

#include "sensors/gnss_sim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/time.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::sim {
namespace {

namespace xs = drivers::xsens;

SimSetup MakeSetup(const std::string& name, uint64_t seed, double duration_s) {
  auto s = MakeSimSetup(name, seed, duration_s);
  EXPECT_TRUE(s.has_value());
  return std::move(*s);
}

/// The PVT item of sample `i`'s frame, encoded and decoded by the drivers.
xs::XsensGnssPvt ThroughXbus(const SimImuSample& sample, const xs::XsensGnssPvt& pvt) {
  std::array<uint8_t, xs::kXbusMaxFrame> frame{};
  const size_t n = EncodeImuFrame(sample, frame, &pvt);
  EXPECT_GT(n, 0u);
  xs::XbusFramer framer;
  EXPECT_EQ(framer.Feed(std::span(frame).first(n)), n);
  xs::XbusFrame f;
  EXPECT_TRUE(framer.Next(&f));
  EXPECT_EQ(f.frame_bytes, n);
  xs::MtData2Sample m;
  EXPECT_EQ(xs::DecodeMtData2(f.payload, &m), xs::MtData2Status::kOk);
  EXPECT_EQ(m.sample_time_fine.value_or(0), sample.sample_time_fine);
  EXPECT_TRUE(m.gnss_pvt.has_value());
  return m.gnss_pvt.value_or(xs::XsensGnssPvt{});
}

Eigen::Vector3d ToEnu(const GnssSimConfig& config, const xs::XsensGnssPvt& p) {
  return LocalEnu(config.origin)
      .ToEnu({p.lat_1e7deg * 1e-7, p.lon_1e7deg * 1e-7, p.height_mm * 1e-3});
}

struct SimRun {
  SimSetup setup;
  std::vector<SimImuSample> imu;
  std::vector<SimGnssFix> fixes;
};

SimRun Simulate(const std::string& name,
                uint64_t seed,
                double duration_s,
                const GnssSimConfig* gnss) {
  SimRun r{MakeSetup(name, seed, duration_s), {}, {}};
  if (gnss != nullptr) r.setup.gnss = *gnss;
  r.imu = SimulateImu(*r.setup.trajectory, r.setup.imu, seed);
  r.fixes = SimulateGnss(*r.setup.trajectory, r.setup.gnss, r.imu, seed);
  return r;
}

TEST(SimGnss, NoiseFreeFixesRoundTripToTheAntennaWithinACentimetre) {
  GnssSimConfig config;
  config.noise.sigma_h_m = config.noise.sigma_v_m = config.noise.velocity_sigma_mps = 0.0;
  const SimRun r = Simulate("aggressive", 5, 40.0, &config);
  ASSERT_NEAR(static_cast<double>(r.fixes.size()), (40.0 - 1.0) * 4.0, 2.0);
  double worst_m = 0.0;
  for (const SimGnssFix& f : r.fixes) {
    const SimImuSample& s = r.imu[f.imu_index];
    ASSERT_TRUE(s.has_gnss_pvt);
    const xs::XsensGnssPvt p = ThroughXbus(s, f.pvt);
    const Kinematics k = r.setup.trajectory->At(NsToSec(s.t_true_ns));
    const Eigen::Vector3d truth = k.p_world + k.R_world_body * config.p_imu_antenna_m;
    worst_m = std::max(worst_m, (ToEnu(config, p) - truth).norm());
    const Eigen::Vector3d v_ned(p.vel_n_mmps * 1e-3, p.vel_e_mmps * 1e-3, p.vel_d_mmps * 1e-3);
    const Eigen::Vector3d v_antenna =
        k.v_world + k.R_world_body * k.omega_body.cross(config.p_imu_antenna_m);
    EXPECT_LT((v_ned - Eigen::Vector3d(v_antenna.y(), v_antenna.x(), -v_antenna.z())).norm(), 2e-3);
    EXPECT_EQ(p.fix_type, 3);
    EXPECT_EQ(p.flags & 0x01, 0x01) << "gnssFixOK";
    EXPECT_EQ(p.valid & 0x03, 0x03) << "validDate, validTime";
    EXPECT_EQ(p.num_sv, 12);
  }
  EXPECT_LT(worst_m, 0.01);
}

TEST(SimGnss, FixesComeAtFourHertzAfterTheFirstFix) {
  const SimRun r = Simulate("short", 6, 20.0, nullptr);
  ASSERT_FALSE(r.fixes.empty());
  EXPECT_GE(r.fixes.front().t_true_ns, kNsPerSec);
  EXPECT_LT(r.fixes.front().t_true_ns, kNsPerSec + 3 * kNsPerMs);
  for (size_t i = 1; i < r.fixes.size(); ++i) {
    const int64_t dt = r.fixes[i].t_true_ns - r.fixes[i - 1].t_true_ns;
    EXPECT_NEAR(static_cast<double>(dt), 250e6, 2.6e6);
    // iTOW counts ms of the GPS week, in step with the fixes.
    EXPECT_NEAR(static_cast<double>(r.fixes[i].pvt.itow_ms - r.fixes[i - 1].pvt.itow_ms),
                static_cast<double>(dt) * 1e-6, 1.0);
  }
  const xs::XsensGnssPvt& p = r.fixes.front().pvt;
  EXPECT_EQ(p.year, 2024);
  EXPECT_EQ(p.month, 1);
  EXPECT_EQ(p.day, 1);
  EXPECT_EQ(p.sec, 1);
  // The frames that carry an item are longer: they arrive after their longer transmission.
  const double tx_long_s =
      (r.setup.imu.frame_bytes + r.setup.imu.gnss_pvt_item_bytes) * 10.0 / r.setup.imu.baud;
  size_t marked = 0;
  for (const SimImuSample& s : r.imu) {
    if (!s.has_gnss_pvt) continue;
    ++marked;
    EXPECT_GE(s.t_rx_ns - s.t_true_ns, SecToNs(tx_long_s));
  }
  EXPECT_EQ(marked, r.fixes.size());
}

/// Over a long drive (32 correlation times) the error's RMS per axis is near its σ, and the
/// reported accuracies are the model's.
TEST(SimGnss, ErrorsFollowTheGaussMarkovModel) {
  const SimRun r = Simulate("loop943", 7, 965.0, nullptr);
  const GnssErrorModel& n = r.setup.gnss.noise;
  Eigen::Vector3d sum2 = Eigen::Vector3d::Zero();
  for (const SimGnssFix& f : r.fixes) {
    const Eigen::Vector3d e =
        ToEnu(r.setup.gnss, ThroughXbus(r.imu[f.imu_index], f.pvt)) - f.p_enu_true_m;
    EXPECT_LT((e - f.error_enu_m).norm(), 0.01);
    sum2 += e.cwiseAbs2();
    EXPECT_EQ(f.pvt.h_acc_mm, static_cast<uint32_t>(std::lround(1.2 * std::sqrt(2.0) * 800.0)));
    EXPECT_EQ(f.pvt.v_acc_mm, 1800u);
  }
  const Eigen::Vector3d rms = (sum2 / static_cast<double>(r.fixes.size())).cwiseSqrt();
  const Eigen::Vector3d sigma(n.sigma_h_m, n.sigma_h_m, n.sigma_v_m);
  std::printf("[ gnss ] %zu fixes, error RMS east %.3f north %.3f up %.3f m\n", r.fixes.size(),
              rms.x(), rms.y(), rms.z());
  for (int a = 0; a < 3; ++a) {
    EXPECT_GT(rms(a), 0.3 * sigma(a)) << "axis " << a;
    EXPECT_LT(rms(a), 2.5 * sigma(a)) << "axis " << a;
  }
  // Correlated: 0.25 s apart the error barely moves (φ = e^(−0.25/30) ≈ 0.992).
  double step2 = 0.0;
  for (size_t i = 1; i < r.fixes.size(); ++i) {
    step2 += (r.fixes[i].error_enu_m - r.fixes[i - 1].error_enu_m).head<2>().squaredNorm();
  }
  const double step_rms = std::sqrt(step2 / static_cast<double>(r.fixes.size() - 1) / 2.0);
  EXPECT_LT(step_rms, 0.2 * n.sigma_h_m);
}

TEST(SimGnss, OutageAndJumpShowUpInTheItems) {
  GnssSimConfig faulty;
  faulty.outages = {{5.0, 2.0}};
  faulty.jumps = {{10.0, 3.0, 8.0}};
  const SimRun clean = Simulate("short", 8, 16.0, nullptr);
  const SimRun r = Simulate("short", 8, 16.0, &faulty);
  ASSERT_EQ(r.fixes.size(), clean.fixes.size());
  size_t no_fix = 0, jumped = 0;
  for (size_t i = 0; i < r.fixes.size(); ++i) {
    const double t_s = NsToSec(r.fixes[i].t_true_ns);
    const xs::XsensGnssPvt p = ThroughXbus(r.imu[r.fixes[i].imu_index], r.fixes[i].pvt);
    if (faulty.outages[0].Contains(t_s)) {
      ++no_fix;
      EXPECT_EQ(p.fix_type, 0);
      EXPECT_EQ(p.flags & 0x01, 0);
      continue;
    }
    EXPECT_EQ(p.fix_type, 3);
    const Eigen::Vector3d offset = ToEnu(r.setup.gnss, p) - ToEnu(r.setup.gnss, clean.fixes[i].pvt);
    if (faulty.jumps[0].Contains(t_s)) {
      ++jumped;
      EXPECT_LT((offset - Eigen::Vector3d(8.0, 0.0, 0.0)).norm(), 0.01) << "t = " << t_s;
      EXPECT_EQ(p.h_acc_mm, clean.fixes[i].pvt.h_acc_mm) << "the receiver does not notice";
    } else {
      EXPECT_LT(offset.norm(), 1e-6);
    }
  }
  EXPECT_NEAR(static_cast<double>(no_fix), 8.0, 1.0);
  EXPECT_NEAR(static_cast<double>(jumped), 12.0, 1.0);
}

TEST(SimGnss, NoGnssMeansNoItems) {
  SimSetup setup = MakeSetup("short", 9, 5.0);
  setup.imu.gnss_pvt_period_s = 0.0;
  const auto imu = SimulateImu(*setup.trajectory, setup.imu, 9);
  EXPECT_TRUE(SimulateGnss(*setup.trajectory, setup.gnss, imu, 9).empty());
}

}  // namespace
}  // namespace swlio::sim
