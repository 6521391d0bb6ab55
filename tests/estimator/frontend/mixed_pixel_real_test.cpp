// Mixed pixels on the real RS-LiDAR-16 capture (shared/data/rs16_washing_house): the sweeps
// decoded as the driver does, each through the front end with the mixed-pixel test at 0.15 m
// (an option, off by default) and off.
// A real sensor's returns merge at edges too, so the test finds some; it takes few points, and
// the edge features stay.

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "swlio/drivers/pcap_file.h"
#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/scan_assembler.h"
#include "swlio/estimator/frontend/front_end.h"
#include "test_data.h"

namespace swlio::estimator {
namespace {

constexpr char kCapture[] = "rs16_washing_house/rs16_msop2244_difop7788.repackaged.pcap";

// The capture's full sweeps (the first and the last are partial).
std::vector<Scan> Sweeps(const std::filesystem::path& path) {
  std::string error;
  auto reader = drivers::PcapReader::Open(path.string(), {}, &error);
  EXPECT_NE(reader, nullptr) << error;
  drivers::LidarConfig lidar;
  lidar.msop_port = 2244;
  drivers::Rs16Decoder decoder(lidar);
  std::vector<std::vector<uint8_t>> msop;
  drivers::UdpDatagram d;
  while (reader && reader->Next(&d)) {
    if (d.dst_port == 7788) decoder.DecodeInfo(d.payload);
    if (d.dst_port == 2244) msop.emplace_back(d.payload.begin(), d.payload.end());
  }
  drivers::ScanAssemblerConfig config;
  config.packets_per_revolution = decoder.PacketsPerRevolution();
  config.revolution_period_ns = static_cast<int64_t>(60e9 / decoder.Rpm());
  drivers::ScanAssembler assembler(config);
  drivers::LidarPacketDecoder::ReturnBuffer buf;
  drivers::AssembledScan out;
  std::vector<Scan> sweeps;
  for (const auto& p : msop) {
    drivers::LidarPacketSummary s;
    if (decoder.DecodeData(p, buf, &s) != drivers::DecodeStatus::kOk) continue;
    assembler.AddPacket(std::span(buf.data(), s.returns), s);
    while (assembler.PopScan(&out)) {
      if (!out.scan.partial) sweeps.push_back(out.scan);
    }
  }
  return sweeps;
}

struct Counts {
  int64_t mixed = 0, occluded = 0, edges = 0, planes = 0;
};

Counts Features(const std::vector<Scan>& sweeps, double tolerance_m) {
  FrontEndConfig config;
  config.features.mixed_pixel_tolerance_m = tolerance_m;
  FrontEnd front_end(config);
  FrontEndOutput out;
  Counts c;
  for (const Scan& scan : sweeps) {
    front_end.Process(scan, &out);
    c.mixed += out.features.mixed;
    c.occluded += out.features.occluded;
    c.edges += static_cast<int64_t>(out.features.edges.size());
    c.planes += static_cast<int64_t>(out.features.planes.size());
  }
  return c;
}

TEST(MixedPixelReal, FewPointsTakenAndTheEdgesStay) {
  SWLIO_REQUIRE_DATA(path, kCapture);
  const std::vector<Scan> sweeps = Sweeps(path);
  ASSERT_GE(sweeps.size(), 30u);
  const Counts on = Features(sweeps, 0.15);
  const Counts off = Features(sweeps, 0.0);
  std::printf(
      "%zu sweeps: mixed %lld, occluded %lld; edges %lld (off %lld), planes %lld (off %lld)\n",
      sweeps.size(), static_cast<long long>(on.mixed), static_cast<long long>(on.occluded),
      static_cast<long long>(on.edges), static_cast<long long>(off.edges),
      static_cast<long long>(on.planes), static_cast<long long>(off.planes));
  EXPECT_EQ(off.mixed, 0);
  EXPECT_GT(on.mixed, 0);
  EXPECT_LT(on.mixed, on.occluded / 20);  // measured: 33 of 31,439 (39 sweeps)
  EXPECT_GT(on.edges, off.edges * 9 / 10);
  EXPECT_GT(on.planes, off.planes * 99 / 100);
}

}  // namespace
}  // namespace swlio::estimator
