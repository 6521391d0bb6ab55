// swlio-decode rs16 / helios16p / vlp16 on the real captures: the JSON summary and CSV the
// issue specifies. Counts that the decoder tests establish independently (raw-byte counts for
// RS16, nebula's reference clouds for the others) are the expectations here.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_data.h"

namespace {

namespace fs = std::filesystem;

std::string RunDecode(const std::string& args) {
  const fs::path tool = fs::read_symlink("/proc/self/exe").parent_path() / "swlio-decode";
  return swlio::test::RunCommand(tool.string() + " " + args + " 2>&1");
}

bool Has(const std::string& json, const std::string& fragment) {
  return json.find(fragment) != std::string::npos;
}

TEST(LidarDecodeCommand, Rs16RealCaptureSummaryAndPoints) {
  SWLIO_REQUIRE_DATA(pcap, "rs16_washing_house/rs16_msop2244_difop7788.repackaged.pcap");
  const fs::path csv = swlio::test::MakeTempDir("rs16cmd") / "points.csv";
  const std::string json =
      RunDecode("rs16 '" + pcap.string() + "' --summary --points '" + csv.string() + "'");
  for (const char* f : {"\"packets_msop\":3000", "\"packets_difop\":40", "\"scans\":41",
                        "\"complete_scans\":39", "\"points\":1063236", "\"gaps\":0", "\"rpm\":600",
                        "\"msop_port\":2244", "\"difop_port\":7788", "\"lens_offset_m\":0.03825"}) {
    EXPECT_TRUE(Has(json, f)) << f << " in " << json;
  }
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "scan,ring,azimuth_deg,x,y,z,intensity,t_offset_ns");
  size_t rows = 0;
  for (std::string line; std::getline(in, line);) {
    // The azimuth column is the point's own, clockwise from +x (x forward, y left).
    double az = 0, x = 0, y = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%*u,%*u,%lf,%lf,%lf", &az, &x, &y), 3) << line;
    const double rho = std::hypot(x, y);
    ASSERT_LT(std::hypot(x - rho * std::cos(az * M_PI / 180), y + rho * std::sin(az * M_PI / 180)),
              1e-3 * rho + 1e-6)
        << line;
    ++rows;
  }
  EXPECT_EQ(rows, 1'063'236u);
  // The manual's formula on request; an implausible offset is refused.
  EXPECT_TRUE(
      Has(RunDecode("rs16 '" + pcap.string() + "' --lens-offset 0"), "\"lens_offset_m\":0,"));
  int exit_code = 0;
  const fs::path tool = fs::read_symlink("/proc/self/exe").parent_path() / "swlio-decode";
  swlio::test::RunCommand(tool.string() + " rs16 '" + pcap.string() + "' --lens-offset 0.5 2>&1",
                          &exit_code);
  EXPECT_NE(exit_code, 0);
}

TEST(LidarDecodeCommand, Helios16pAndVlp16Summaries) {
  SWLIO_REQUIRE_DATA(helios, "rs_helios16p_nebula/helios16p_msop6699_difop7788.repackaged.pcap");
  SWLIO_REQUIRE_DATA(vlp, "velodyne_nebula/vlp16/vlp16_port2368.repackaged.pcap");
  const std::string h = RunDecode("helios16p '" + helios.string() + "' --summary");
  for (const char* f :
       {"\"packets_msop\":750", "\"packets_difop\":1", "\"scans\":6", "\"gaps\":0", "\"rpm\":600",
        "\"calibration_from_difop\":true", "\"lens_offset_m\":0.03498"}) {
    EXPECT_TRUE(Has(h, f)) << f << " in " << h;
  }
  const std::string v = RunDecode("vlp16 '" + vlp.string() + "' --summary");
  for (const char* f :
       {"\"packets_msop\":603", "\"scans\":5", "\"gaps\":0", "\"lens_offset_m\":0,"}) {
    EXPECT_TRUE(Has(v, f)) << f << " in " << v;
  }
}

TEST(LidarDecodeCommand, MissingFileIsAnErrorNotACrash) {
  const std::string out = RunDecode("rs16 /nonexistent.pcap --summary");
  EXPECT_TRUE(Has(out, "swlio-decode rs16:")) << out;
}

}  // namespace
