// swlio-bag info on the real RS16 bag (counts and span from its README/metadata.yaml) and on an
// MCAP written here with the problems `info` must report: a type swlio does not read, a
// message that does not decode, header stamps out of order and repeated, a damaged chunk.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "swlio/drivers/bag/mcap_writer.h"
#include "swlio/drivers/bag/message_encoder.h"
#include "test_data.h"

namespace {

namespace fs = std::filesystem;
namespace bag = swlio::drivers::bag;

std::string RunBag(const std::string& args, int* code) {
  const fs::path tool = fs::read_symlink("/proc/self/exe").parent_path() / "swlio-bag";
  return swlio::test::RunCommand(tool.string() + " " + args + " 2>&1", code);
}

void WriteBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

bool Has(const std::string& out, const std::string& fragment) {
  return out.find(fragment) != std::string::npos;
}

TEST(BagInfoCommand, RealRs16Bag) {
  SWLIO_REQUIRE_DATA(dir, "rs16_washing_house/metadata.yaml");
  int code = -1;
  const std::string out = RunBag("info '" + dir.parent_path().string() + "'", &code);
  EXPECT_EQ(code, 0) << out;
  for (const char* f : {"storage:   rosbag2 sqlite3 (db schema 2)", "duration:  3.903 s",
                        "messages:  80", "/rslidar_packets        rslidar_msg/msg/RslidarScan",
                        "40 msgs", "[LiDAR: RslidarScan, 3000 packets]", "10.0 Hz"}) {
    EXPECT_TRUE(Has(out, f)) << f << " in\n" << out;
  }
  EXPECT_FALSE(Has(out, "warnings:")) << out;
}

TEST(BagInfoCommand, ReportsWhatIsWrong) {
  bag::McapWriterOptions o;
  o.chunk_bytes = 2000;
  o.compression = bag::Compression::kNone;
  auto w = bag::McapWriter::CreateInMemory(o);
  const uint16_t imu =
      w->AddChannel(w->AddSchema("sensor_msgs/msg/Imu", "ros2msg", ""), "/imu", "cdr");
  const uint16_t chatter =
      w->AddChannel(w->AddSchema("std_msgs/msg/String", "ros2msg", ""), "/chatter", "cdr");
  const int64_t t0 = 1'700'000'000'000'000'000;
  int64_t log = t0;
  for (const int64_t stamp : {10, 20, 15, 15, 30}) {  // one backwards, one repeated (15, 15)
    bag::ImuMsg m;
    m.header = {t0 + stamp, "imu_link"};
    log += 1000;
    w->Write(imu, log, t0, bag::EncodeImu(m, bag::MessageEncoding::kCdr));
  }
  w->Write(imu, log + 1000, t0, std::vector<uint8_t>{0, 1, 0, 0, 1, 2, 3});  // #5 cut short
  w->Write(chatter, log + 2000, t0, std::vector<uint8_t>{0, 1, 0, 0, 1, 0, 0, 0, 0});
  std::string error;
  ASSERT_TRUE(w->Close(&error)) << error;
  const fs::path file = swlio::test::MakeTempDir("baginfo") / "bad.mcap";
  WriteBytes(file, w->bytes());
  int code = -1;
  const std::string out = RunBag("info '" + file.string() + "'", &code);
  EXPECT_EQ(code, 0) << out;
  for (const char* f :
       {"storage:   mcap (profile 'ros2'", "/imu      sensor_msgs/msg/Imu", "6 msgs",
        "/chatter: type std_msgs/msg/String is not read by swlio",
        "/imu: 1 messages do not decode as sensor_msgs/msg/Imu (first #5:",
        "/imu: 1 header stamps earlier than the one before", "/imu: 1 repeated header stamps"}) {
    EXPECT_TRUE(Has(out, f)) << f << " in\n" << out;
  }
}

TEST(BagInfoCommand, MissingAndForeignFilesAreErrors) {
  int code = -1;
  std::string out = RunBag("info /nonexistent/bag.mcap", &code);
  EXPECT_EQ(code, 2);
  EXPECT_TRUE(Has(out, "/nonexistent/bag.mcap: no such file")) << out;
  const fs::path text = swlio::test::MakeTempDir("baginfo") / "notes.db3";
  const std::string junk = "plain text, long enough to be judged by its bytes\n";
  WriteBytes(text, std::vector<uint8_t>(junk.begin(), junk.end()));
  out = RunBag("info '" + text.string() + "'", &code);
  EXPECT_EQ(code, 2);
  EXPECT_TRUE(Has(out, "notes.db3: not a bag")) << out;
}

}  // namespace
