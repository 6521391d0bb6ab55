#include "swlio/drivers/scan_assembler.h"

#include <gtest/gtest.h>

#include <vector>

#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/rs16_encoder.h"

namespace swlio::drivers {
namespace {

constexpr int64_t kT0 = 1'500'000'000'000'000'000;
constexpr double kBlockStepDeg = 0.3996;  // 600 rpm, 111 µs per block
constexpr int64_t kPacketNs = int64_t{12} * 111'000;

// Synthetic RS16 stream at 600 rpm through the real encoder and decoder.
class Rs16Stream {
 public:
  explicit Rs16Stream(double start_deg) : start_deg_(start_deg) {
    LidarConfig config;
    config.min_range_m = 0.0;
    decoder_ = std::make_unique<Rs16Decoder>(config);
  }
  // Packet k, optionally with a time shift.
  void Decode(int k,
              int64_t time_shift_ns,
              std::vector<LidarReturn>* returns,
              LidarPacketSummary* summary) {
    Rs16MsopContent c;
    c.t_sensor_ns = kT0 + k * kPacketNs + time_shift_ns;
    for (size_t b = 0; b < 12; ++b) {
      c.blocks[b].azimuth_deg =
          start_deg_ + kBlockStepDeg * static_cast<double>(12 * k + static_cast<int>(b));
      c.blocks[b].range_m.fill(8.0f);
    }
    std::vector<uint8_t> packet(1248);
    ASSERT_TRUE(EncodeRs16Msop(c, packet));
    LidarPacketDecoder::ReturnBuffer buf;
    ASSERT_EQ(decoder_->DecodeData(packet, buf, summary), DecodeStatus::kOk);
    returns->assign(buf.begin(), buf.begin() + summary->returns);
  }
  ScanAssemblerConfig Config(double cut_deg) const {
    ScanAssemblerConfig c;
    c.cut_angle_deg = cut_deg;
    c.packets_per_revolution = decoder_->PacketsPerRevolution();
    c.revolution_period_ns = 100'000'000;
    return c;
  }

 private:
  double start_deg_;
  std::unique_ptr<Rs16Decoder> decoder_;
};

struct AssemblyRun {
  std::vector<AssembledScan> scans;
  ScanAssemblerStats stats;
};

// Feeds packets [0, n) except `skip`, shifting times from packet `shift_from` on.
AssemblyRun Assemble(double start_deg,
                     double cut_deg,
                     int n,
                     std::vector<int> skip = {},
                     int shift_from = -1,
                     int64_t shift_ns = 0) {
  Rs16Stream stream(start_deg);
  ScanAssembler assembler(stream.Config(cut_deg));
  AssemblyRun run;
  std::vector<LidarReturn> returns;
  LidarPacketSummary summary;
  AssembledScan out;
  for (int k = 0; k < n; ++k) {
    if (std::find(skip.begin(), skip.end(), k) != skip.end()) continue;
    stream.Decode(k, shift_from >= 0 && k >= shift_from ? shift_ns : 0, &returns, &summary);
    assembler.AddPacket(returns, summary, 1000 + k);
    while (assembler.PopScan(&out)) run.scans.push_back(out);
  }
  assembler.Flush();
  while (assembler.PopScan(&out)) run.scans.push_back(out);
  run.stats = assembler.stats();
  return run;
}

TEST(ScanAssembler, CutsAtTheCutAngleAndFlagsStreamEnds) {
  // Start at 100°, 3.5 turns: crossings of 0° after 260°, 620°, 980° → 4 sweeps.
  const int n = static_cast<int>(3.5 * 360 / (12 * kBlockStepDeg));
  const AssemblyRun run = Assemble(100.0, 0.0, n);
  ASSERT_EQ(run.scans.size(), 4u);
  EXPECT_EQ(run.stats.gaps, 0u);
  EXPECT_EQ(run.stats.missing_packets, 0u);
  EXPECT_TRUE(run.scans.front().scan.partial);
  EXPECT_FALSE(run.scans.front().started_at_cut);
  EXPECT_TRUE(run.scans.back().scan.partial);
  EXPECT_FALSE(run.scans.back().ended_at_cut);
  size_t points = 0;
  for (size_t i = 0; i < run.scans.size(); ++i) {
    const AssembledScan& s = run.scans[i];
    EXPECT_EQ(s.scan.seq, i);
    points += s.scan.points.size();
    if (i == 0 || i + 1 == run.scans.size()) continue;
    EXPECT_FALSE(s.scan.partial) << i;
    EXPECT_LT(s.first_azimuth_deg, 0.5f);
    EXPECT_GT(s.last_azimuth_deg, 359.5f);
    EXPECT_NEAR(static_cast<double>(s.scan.t_end_ns - s.scan.t_start_ns), 1e8, 2e5);
    EXPECT_EQ(s.scan.points.back().dt_ns, s.scan.t_end_ns - s.scan.t_start_ns);
    EXPECT_EQ(s.scan.points.front().dt_ns, 0);
    EXPECT_NEAR(static_cast<double>(s.packets), 75.1, 1.5);
    EXPECT_GE(s.host_rx_last_ns, s.host_rx_first_ns);
  }
  EXPECT_EQ(points, static_cast<size_t>(n) * 384u);
  EXPECT_EQ(run.stats.scans, 4u);
  EXPECT_EQ(run.stats.partial_scans, 2u);
}

TEST(ScanAssembler, OtherCutAngle) {
  const int n = static_cast<int>(2.0 * 360 / (12 * kBlockStepDeg));
  const AssemblyRun run = Assemble(10.0, 90.0, n);  // crossings of 90° after 80°, 440° → 3 sweeps
  ASSERT_EQ(run.scans.size(), 3u);
  const AssembledScan& middle = run.scans[1];
  EXPECT_FALSE(middle.scan.partial);
  EXPECT_NEAR(middle.first_azimuth_deg, 90.0f, 0.5f);
  EXPECT_NEAR(middle.last_azimuth_deg, 90.0f, 0.5f);
  EXPECT_GE(middle.first_azimuth_deg, 90.0f);
  EXPECT_LT(middle.last_azimuth_deg, 90.0f);
}

TEST(ScanAssembler, MissingPacketsAreCountedAndFlagTheirSweep) {
  const int n = static_cast<int>(3.5 * 360 / (12 * kBlockStepDeg));
  // Sweep 1 spans packets ~55–129 (crossings after 260° and 620°, 4.795° per packet).
  const AssemblyRun run = Assemble(100.0, 0.0, n, {100, 101, 102, 110});
  EXPECT_EQ(run.stats.gaps, 2u);
  EXPECT_EQ(run.stats.missing_packets, 4u);
  ASSERT_EQ(run.scans.size(), 4u);  // small gaps do not split sweeps
  EXPECT_EQ(run.scans[1].missing_packets, 4u);
  EXPECT_TRUE(run.scans[1].scan.partial);
  EXPECT_FALSE(run.scans[2].scan.partial);
}

TEST(ScanAssembler, TimeDiscontinuityClosesTheSweep) {
  const int n = static_cast<int>(3.5 * 360 / (12 * kBlockStepDeg));
  const AssemblyRun run = Assemble(100.0, 0.0, n, {}, 150, -1'000'000'000);
  EXPECT_EQ(run.stats.discontinuities, 1u);
  EXPECT_EQ(run.stats.gaps, 0u);
  // Sweeps: [0, 54] partial, [55, 129] complete, [130, 149] closed by the jump,
  // [150, 204] begun by it, [205, end) closed by Flush.
  ASSERT_EQ(run.scans.size(), 5u);
  EXPECT_FALSE(run.scans[1].scan.partial);
  EXPECT_TRUE(run.scans[2].scan.partial);
  EXPECT_TRUE(run.scans[2].started_at_cut);
  EXPECT_FALSE(run.scans[2].ended_at_cut);
  EXPECT_TRUE(run.scans[3].scan.partial);
  EXPECT_FALSE(run.scans[3].started_at_cut);
  EXPECT_TRUE(run.scans[3].ended_at_cut);
  for (const auto& s : run.scans) {
    for (const auto& p : s.scan.points) ASSERT_GE(p.dt_ns, 0);
  }
}

TEST(ScanAssembler, LongForwardJumpCountsMissingAndCloses) {
  const int n = 300;
  const AssemblyRun run =
      Assemble(100.0, 0.0, n, {}, 150, int64_t{3} * 100'000'000 + 4 * kPacketNs);
  EXPECT_EQ(run.stats.discontinuities, 1u);
  EXPECT_EQ(run.stats.gaps, 1u);
  // Time step 1 + 229.225 packets of 1.332 ms → 229 missing.
  EXPECT_EQ(run.stats.missing_packets, 229u);
}

TEST(ScanAssembler, JitterAroundTheCutSplitsOnce) {
  ScanAssemblerConfig config;
  ScanAssembler assembler(config);
  const std::vector<float> azimuths = {350.0f, 355.0f,  359.8f, 0.1f, 359.9f,
                                       0.2f,   359.95f, 0.3f,   10.0f};
  LidarPacketSummary summary;
  std::vector<LidarReturn> returns;
  int64_t t = 0;
  for (float a : azimuths) {
    LidarReturn r;
    r.azimuth_deg = a;
    r.t_sensor_ns = t += 1000;
    returns.push_back(r);
  }
  summary.first_azimuth_deg = 350.0f;
  summary.t_sensor_ns = 1000;
  EXPECT_EQ(assembler.AddPacket(returns, summary), 1);
  EXPECT_EQ(assembler.Flush(), 2);
  AssembledScan a, b;
  ASSERT_TRUE(assembler.PopScan(&a));
  ASSERT_TRUE(assembler.PopScan(&b));
  EXPECT_EQ(a.scan.points.size(), 3u);
  EXPECT_EQ(b.scan.points.size(), 6u);
  EXPECT_TRUE(b.started_at_cut);
  EXPECT_FALSE(assembler.PopScan(&a));
}

TEST(ScanAssembler, LaggingConsumerDropsOldestSweeps) {
  ScanAssembler assembler(ScanAssemblerConfig{});
  LidarPacketSummary summary;
  for (int turn = 0; turn < 6; ++turn) {
    std::vector<LidarReturn> returns(4);
    for (int i = 0; i < 4; ++i)
      returns[static_cast<size_t>(i)].azimuth_deg = 90.0f * static_cast<float>(i) + 1.0f;
    summary.first_azimuth_deg = 1.0f;
    summary.t_sensor_ns = (turn + 1) * 100'000'000LL / 75;  // keep time steps small
    assembler.AddPacket(returns, summary);
  }
  EXPECT_EQ(assembler.stats().scans, 5u);
  EXPECT_EQ(assembler.stats().dropped_scans, 2u);
  AssembledScan out;
  ASSERT_TRUE(assembler.PopScan(&out));
  EXPECT_EQ(out.scan.seq, 2u);
}

}  // namespace
}  // namespace swlio::drivers
