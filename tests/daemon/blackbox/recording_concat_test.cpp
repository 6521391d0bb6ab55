// Segments joined into one recording (recording_concat.h): one pcap header, the serial bytes
// and their index continuous, one header per CSV, every text line kept.

#include "swlio/daemon/blackbox/recording_concat.h"

#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <sstream>

#include "swlio/daemon/recording/recording_files.h"
#include "swlio/drivers/pcap_file.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

std::vector<std::string> Lines(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

/// A segment with `packets` LiDAR datagrams, 3 serial reads of 10 bytes and 2 health rows.
void WriteSegment(const std::filesystem::path& dir,
                  const DaemonConfig& config,
                  int64_t t0,
                  int packets) {
  RecordingSetup setup;
  setup.config = &config;
  setup.config_text = "config_version: 1\n";
  setup.msop_port = 6699;
  setup.difop_port = 7788;
  std::string error;
  auto f = RecordingFiles::Open(dir, setup, {t0, 5}, &error);
  ASSERT_NE(f, nullptr) << error;
  std::array<uint8_t, 1248> packet{};
  for (int i = 0; i < packets; ++i) f->Packet(t0 + i * 1000, false, packet);
  std::array<uint8_t, 10> bytes{};
  for (int i = 0; i < 3; ++i) f->Serial(t0 + i, bytes);
  f->HealthRow(std::to_string(t0) + ",a");
  f->HealthRow(std::to_string(t0 + 1) + ",b");
  f->LogLine("line of " + std::to_string(t0));
  ASSERT_TRUE(f->Close()) << f->error();
}

TEST(RecordingConcat, JoinsSegmentsIntoOneReadableRecording) {
  const auto dir = test::MakeTempDir("recording_concat");
  const DaemonConfig config;
  WriteSegment(dir / "a", config, 1'000'000'000, 4);
  WriteSegment(dir / "b", config, 2'000'000'000, 5);
  std::string error;
  int beats = 0;
  ASSERT_TRUE(ConcatenateRecordings(
      {dir / "a", dir / "b"}, dir / "out", [&] { ++beats; }, &error))
      << error;
  EXPECT_GT(beats, 0);
  // pcap: every record once, under one global header.
  auto reader = drivers::PcapReader::Open((dir / "out" / "lidar.pcap").string(), {}, &error);
  ASSERT_NE(reader, nullptr) << error;
  int records = 0;
  drivers::UdpDatagram d;
  while (reader->Next(&d)) ++records;
  EXPECT_EQ(records, 9);
  // Serial: 60 bytes; the index runs on across the join.
  EXPECT_EQ(std::filesystem::file_size(dir / "out" / "imu.xbus"), 60u);
  const std::vector<std::string> rx = Lines(dir / "out" / "imu.rx.csv");
  ASSERT_EQ(rx.size(), 7u);
  EXPECT_EQ(rx[0], "byte_offset,bytes,t_rx_ns");
  EXPECT_EQ(rx[4], "30,10,2000000000");
  EXPECT_EQ(rx[6], "50,10,2000000002");
  const std::vector<std::string> health = Lines(dir / "out" / "health.csv");
  ASSERT_EQ(health.size(), 5u);
  EXPECT_EQ(health[0].rfind("t_ns,utc,", 0), 0u);
  EXPECT_EQ(health[3], "2000000000,a");
  EXPECT_EQ(Lines(dir / "out" / "log.txt"),
            (std::vector<std::string>{"line of 1000000000", "line of 2000000000"}));
  EXPECT_EQ(Lines(dir / "out" / "clock_offsets.csv").size(), 3u);  // header + one per part
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "manifest.yaml"));
  EXPECT_EQ(Lines(dir / "out" / "config.yaml"), std::vector<std::string>{"config_version: 1"});
  // The output must not exist yet: nothing is overwritten.
  EXPECT_FALSE(ConcatenateRecordings({dir / "a"}, dir / "out", {}, &error));
  EXPECT_NE(error.find("exists"), std::string::npos) << error;
}

}  // namespace
}  // namespace swlio::daemon
