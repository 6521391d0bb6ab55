// Simulator → recorder → replay path: RS16 encoder → PcapWriter → PcapReader → decoder →
// scan assembler, at 1200 rpm with UTC header times and two packets lost on the way.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "swlio/drivers/pcap_file.h"
#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/rs16_encoder.h"
#include "swlio/drivers/scan_assembler.h"
#include "test_data.h"

namespace swlio::drivers {
namespace {

constexpr double kStepDeg = 1200.0 * 6.0 * 111e-6;  // azimuth per 111 µs block at 1200 rpm
constexpr int64_t kT0 = 1'700'000'000'000'000'000;

// A simulated scene: the range seen by a laser depends on the block azimuth and the slot.
float SceneRange(double azimuth_deg, size_t slot) {
  return static_cast<float>(4.0 + 2.0 * std::sin(azimuth_deg * 3.14159265 / 180.0) +
                            0.05 * static_cast<double>(slot % 16));
}

TEST(Rs16Pipeline, EncodeRecordReplayDecodeAssemble) {
  const auto path = test::MakeTempDir("rs16_pipeline") / "sim.pcap";
  const int packets = 120;  // 3.2 revolutions at 37.5 packets per revolution
  {
    auto writer = PcapWriter::Create(path.string(), {}, nullptr);
    ASSERT_NE(writer, nullptr);
    std::vector<uint8_t> bytes(1248);
    Rs16DifopContent info;
    info.rpm = 1200;
    for (int k = 0; k < packets; ++k) {
      const int64_t t = kT0 + int64_t{k} * 12 * 111'000;
      if (k % 10 == 0) {
        info.t_sensor_ns = t;
        ASSERT_TRUE(EncodeRs16Difop(info, bytes));
        ASSERT_TRUE(writer->Write(t, 7788, 7788, bytes));
      }
      if (k == 50 || k == 51) continue;  // lost on the wire
      Rs16MsopContent c;
      c.t_sensor_ns = t;
      c.time_format = rs16::TimeFormat::kUtc;
      for (size_t b = 0; b < 12; ++b) {
        c.blocks[b].azimuth_deg =
            30.0 + kStepDeg * static_cast<double>(12 * k + static_cast<int>(b));
        for (size_t s = 0; s < 32; ++s)
          c.blocks[b].range_m[s] = SceneRange(c.blocks[b].azimuth_deg, s);
      }
      ASSERT_TRUE(EncodeRs16Msop(c, bytes));
      ASSERT_TRUE(writer->Write(t + 500'000, 6699, 6699, bytes));  // host receives 0.5 ms later
    }
  }

  std::string error;
  PcapUdpFilter filter;
  filter.dst_ports = {6699, 7788};
  auto reader = PcapReader::Open(path.string(), filter, &error);
  ASSERT_NE(reader, nullptr) << error;
  LidarConfig config;
  Rs16Decoder decoder(config, {rs16::TimeFormat::kAuto, ReturnMode::kStrongest});
  ScanAssembler assembler(ScanAssemblerConfig{});
  LidarPacketDecoder::ReturnBuffer buf;
  std::vector<AssembledScan> scans;
  AssembledScan out;
  UdpDatagram d;
  int msop = 0;
  while (reader->Next(&d)) {
    if (d.dst_port == 7788) {
      ASSERT_EQ(decoder.DecodeInfo(d.payload), DecodeStatus::kOk);
      assembler.SetNominal(decoder.PacketsPerRevolution(), std::llround(60e9 / decoder.Rpm()));
      continue;
    }
    LidarPacketSummary s;
    ASSERT_EQ(decoder.DecodeData(d.payload, buf, &s), DecodeStatus::kOk);
    EXPECT_EQ(s.t_sensor_ns + 500'000, d.t_ns);
    for (uint32_t i = 0; i < s.returns; ++i) {
      const int block = buf[i].slot / 32;
      const double block_az = s.first_azimuth_deg + kStepDeg * block;
      // 2.5 mm distance quantization + ≤ 0.2 mm from the 0.01° azimuth rounding in the scene.
      ASSERT_NEAR(buf[i].range_m, SceneRange(block_az, buf[i].slot), 0.0027);
    }
    assembler.AddPacket(std::span(buf.data(), s.returns), s, d.t_ns);
    while (assembler.PopScan(&out)) scans.push_back(out);
    ++msop;
  }
  assembler.Flush();
  while (assembler.PopScan(&out)) scans.push_back(out);

  EXPECT_EQ(msop, packets - 2);
  EXPECT_EQ(decoder.Rpm(), 1200.0);
  EXPECT_NEAR(decoder.PacketsPerRevolution(), 37.54, 0.01);
  EXPECT_EQ(assembler.stats().gaps, 1u);
  EXPECT_EQ(assembler.stats().missing_packets, 2u);
  // Start at 30°: cut crossings after 330°, 690°, 1050° of 1151° → 4 sweeps; the lost packets
  // (azimuth ~150° of the second turn) fall in the second sweep.
  ASSERT_EQ(scans.size(), 4u);
  EXPECT_TRUE(scans[1].scan.partial);
  EXPECT_EQ(scans[1].missing_packets, 2u);
  EXPECT_FALSE(scans[2].scan.partial);
  EXPECT_NEAR(static_cast<double>(scans[2].scan.t_end_ns - scans[2].scan.t_start_ns), 5e7, 2e5);
  // Host receive times travel alongside: the first packet of a sweep arrived 0.5 ms after its
  // first firing, and the sweep's first return lies within that packet (≤ 1.332 ms later).
  const int64_t rx_minus_start = scans[2].host_rx_first_ns - scans[2].scan.t_start_ns;
  EXPECT_LE(rx_minus_start, 500'000);
  EXPECT_GE(rx_minus_start, 500'000 - 12 * 111'000);
}

}  // namespace
}  // namespace swlio::drivers
