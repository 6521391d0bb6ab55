// swlio-decode xsens, run as a program on the real einride capture: the --summary JSON
// carries the required counters, and --csv writes one row per MTData2 message.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_data.h"

namespace swlio::tools {
namespace {

namespace fs = std::filesystem;

/// build/bin/swlio-decode, beside this test program; empty when not built.
fs::path DecodeTool() { return test::ToolPath("swlio-decode"); }

using test::RunCommand;

TEST(XsensCommand, SummaryJsonHasTheRequiredCounters) {
  SWLIO_REQUIRE_DATA(bin, "xsens_einride_mti-g-710/1/output.bin");
  const fs::path tool = DecodeTool();
  if (tool.empty()) GTEST_SKIP() << "swlio-decode not built next to the tests";
  const std::string json = RunCommand(tool.string() + " xsens '" + bin.string() + "' --summary");
  EXPECT_NE(json.find("\"frames\": 100,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"frames_by_mid\": {\"0x36\": 100}"), std::string::npos) << json;
  EXPECT_NE(json.find("\"checksum_errors\": 0,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"skipped_bytes\": 0,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"counter_gaps\": 0,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"first_packet_counter\": 43398"), std::string::npos) << json;
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.substr(json.size() - 2), "}\n");
}

TEST(XsensCommand, CsvHasOneRowPerMessage) {
  SWLIO_REQUIRE_DATA(bin, "xsens_einride_mti-g-710/1/output.bin");
  SWLIO_REQUIRE_DATA(golden, "xsens_einride_mti-g-710/1/output.golden");
  const fs::path tool = DecodeTool();
  if (tool.empty()) GTEST_SKIP() << "swlio-decode not built next to the tests";
  const fs::path csv = test::MakeTempDir("xsens_csv") / "out.csv";
  RunCommand(tool.string() + " xsens '" + bin.string() + "' --csv '" + csv.string() + "'");
  std::ifstream in(csv);
  std::string header, first;
  ASSERT_TRUE(std::getline(in, header));
  EXPECT_EQ(header.rfind("frame,packet_counter,sample_time_fine,", 0), 0u);
  ASSERT_TRUE(std::getline(in, first));
  size_t rows = 1;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 100u);
  // Row 0: packet counter, and acc_x equal to the golden file's first Acceleration X.
  std::vector<std::string> cells;
  std::stringstream ss(first);
  for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
  ASSERT_GT(cells.size(), 6u);
  EXPECT_EQ(cells[1], "43398");
  std::ifstream g(golden);
  std::string line;
  while (std::getline(g, line) && line.rfind("Acceleration(", 0) != 0) {
  }
  ASSERT_TRUE(std::getline(g, line));  // "  X:-0.017374228686094284"
  EXPECT_EQ(std::stod(cells[6]), std::stod(line.substr(line.find(':') + 1)));
}

}  // namespace
}  // namespace swlio::tools
