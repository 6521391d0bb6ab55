// OpenBag: the container from the first bytes, rosbag2 folders with and without metadata.yaml,
// split bags merged by time, rosbag2's compression modes, and the errors for everything else.

#include <gtest/gtest.h>
#include <zstd.h>

#include <fstream>
#include <string>
#include <vector>

#include "bag_test_util.h"
#include "db3_builder.h"
#include "ros1_bag_writer.h"
#include "swlio/drivers/bag/bag_open.h"
#include "swlio/drivers/bag/mcap_writer.h"
#include "swlio/drivers/bag/rosbag2_metadata.h"
#include "test_data.h"

namespace swlio::drivers::bag {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;

void WriteFile(const fs::path& p, const Bytes& b) {
  std::ofstream(p, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

Bytes SmallMcap() {
  McapWriterOptions o;
  auto w = McapWriter::CreateInMemory(o);
  const uint16_t ch = w->AddChannel(0, "/t", "cdr");
  w->Write(ch, 5, 5, Bytes{0, 1, 0, 0});
  std::string error;
  EXPECT_TRUE(w->Close(&error));
  return w->bytes();
}

Bytes SmallRos1() {
  test::Ros1BagWriter w;
  w.AddConnection({0, "/t", "std_msgs/Empty", "*", ""});
  w.Write(0, 5, {});
  return w.Finish();
}

TEST(BagOpen, DetectsTheContainerFromItsBytesNotItsName) {
  const auto dir = test::MakeTempDir("open");
  WriteFile(dir / "really_mcap.db3", SmallMcap());
  WriteFile(dir / "really_ros1.mcap", SmallRos1());
  std::string error;
  auto a = OpenBag((dir / "really_mcap.db3").string(), {}, &error);
  ASSERT_NE(a, nullptr) << error;
  EXPECT_EQ(a->StorageDescription().rfind("mcap", 0), 0u);
  auto b = OpenBag((dir / "really_ros1.mcap").string(), {}, &error);
  ASSERT_NE(b, nullptr) << error;
  EXPECT_EQ(b->StorageDescription().rfind("ROS 1", 0), 0u);
  EXPECT_EQ(test::ReadAll(*b).size(), 1u);
  const std::string sqlite = std::string("SQLite format 3") + '\0';
  EXPECT_EQ(DetectBagFormat(Bytes(sqlite.begin(), sqlite.end()), "x"), BagFormat::kRosbag2Sqlite);
  EXPECT_EQ(DetectBagFormat(Bytes(20, 'x'), "x.db3"), BagFormat::kUnknown);
  EXPECT_EQ(DetectBagFormat({}, "cut.mcap"), BagFormat::kMcap);
}

TEST(BagOpen, RefusesWhatIsNoBag) {
  const auto dir = test::MakeTempDir("open");
  std::ofstream(dir / "notes.txt") << "a text file that is long enough to look at\n";
  std::string error;
  EXPECT_EQ(OpenBag((dir / "notes.txt").string(), {}, &error), nullptr);
  EXPECT_NE(error.find("notes.txt: not a bag"), std::string::npos) << error;
  EXPECT_EQ(OpenBag((dir / "missing.bag").string(), {}, &error), nullptr);
  EXPECT_NE(error.find("missing.bag"), std::string::npos) << error;
  fs::create_directory(dir / "empty");
  EXPECT_EQ(OpenBag((dir / "empty").string(), {}, &error), nullptr);
  EXPECT_NE(error.find("without .db3 or .mcap"), std::string::npos) << error;
  WriteFile(dir / "bag_0.db3.zstd", Bytes(40, 1));
  EXPECT_EQ(OpenBag((dir / "bag_0.db3.zstd").string(), {}, &error), nullptr);
  EXPECT_NE(error.find("zstd -d"), std::string::npos) << error;
}

TEST(BagOpen, RealRosbag2FolderAndFile) {
  SWLIO_REQUIRE_DATA(db3, "rs16_washing_house/rosbag2_2022_08_16-11_55_30_0.db3");
  std::string error;
  for (const fs::path& p : {db3, db3.parent_path()}) {
    auto r = OpenBag(p.string(), {}, &error);
    ASSERT_NE(r, nullptr) << error;
    EXPECT_EQ(r->topics().size(), 2u);
    EXPECT_EQ(test::ReadAll(*r).size(), 80u) << p;
  }
  Rosbag2Metadata m;
  ASSERT_TRUE(ReadRosbag2Metadata(db3.parent_path() / "metadata.yaml", &m, &error)) << error;
  EXPECT_EQ(m.version, 4);
  EXPECT_EQ(m.storage_identifier, "sqlite3");
  ASSERT_EQ(m.relative_file_paths.size(), 1u);
  EXPECT_EQ(m.relative_file_paths[0], "rosbag2_2022_08_16-11_55_30_0.db3");
  EXPECT_EQ(m.compression_mode, "");
}

/// A split bag: three files whose times interleave; file k holds times k, k+3, k+6, …
fs::path SplitBag(bool with_metadata) {
  const auto dir = test::MakeTempDir("split");
  const std::vector<std::string> names = {"bag_0.db3", "bag_2.db3", "bag_10.db3"};
  for (size_t k = 0; k < names.size(); ++k) {
    std::vector<test::Db3Message> ms;
    for (int64_t t = static_cast<int64_t>(k); t < 30; t += 3) {
      ms.push_back({1, t, {0, 1, 0, 0, static_cast<uint8_t>(t)}});
    }
    test::WriteDb3(dir / names[k], 3, {{1, "/imu", "sensor_msgs/msg/Imu", "cdr", ""}}, ms);
  }
  if (with_metadata) {
    std::ofstream(dir / "metadata.yaml")
        << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
           "  relative_file_paths:\n    - bag_0.db3\n    - bag_2.db3\n    - bag_10.db3\n"
           "  compression_format: \"\"\n  compression_mode: \"\"\n";
  }
  return dir;
}

TEST(BagOpen, SplitBagsMergeByTime) {
  for (const bool with_metadata : {true, false}) {
    std::string error;
    auto r = OpenBag(SplitBag(with_metadata).string(), {}, &error);
    ASSERT_NE(r, nullptr) << error;
    ASSERT_EQ(r->topics().size(), 1u);
    EXPECT_EQ(r->topics()[0].message_count, 30u);
    EXPECT_EQ(r->topics()[0].first_log_time_ns, 0);
    EXPECT_EQ(r->topics()[0].last_log_time_ns, 29);
    EXPECT_NE(r->StorageDescription().find("3 files"), std::string::npos);
    const auto all = test::ReadAll(*r);
    ASSERT_EQ(all.size(), 30u);
    for (size_t i = 0; i < all.size(); ++i) {
      EXPECT_EQ(all[i].log_time_ns, static_cast<int64_t>(i));
      EXPECT_EQ(all[i].data.back(), i);
      EXPECT_EQ(all[i].index, i);
    }
  }
}

TEST(BagOpen, Rosbag2CompressionModes) {
  const auto dir = test::MakeTempDir("compressed");
  const Bytes cdr = {0, 1, 0, 0, 7, 7, 7, 7};
  Bytes z(ZSTD_compressBound(cdr.size()));
  z.resize(ZSTD_compress(z.data(), z.size(), cdr.data(), cdr.size(), 1));
  test::WriteDb3(dir / "c_0.db3", 3, {{1, "/imu", "sensor_msgs/msg/Imu", "cdr", ""}}, {{1, 1, z}});
  std::ofstream(dir / "metadata.yaml")
      << "rosbag2_bagfile_information:\n  version: 5\n  relative_file_paths:\n    - c_0.db3\n"
         "  compression_format: zstd\n  compression_mode: MESSAGE\n";
  std::string error;
  auto r = OpenBag(dir.string(), {}, &error);
  ASSERT_NE(r, nullptr) << error;
  const auto all = test::ReadAll(*r);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].data, cdr);
  std::ofstream(dir / "metadata.yaml")
      << "rosbag2_bagfile_information:\n  relative_file_paths:\n    - c_0.db3.zstd\n"
         "  compression_format: zstd\n  compression_mode: FILE\n";
  EXPECT_EQ(OpenBag(dir.string(), {}, &error), nullptr);
  EXPECT_NE(error.find("file-compressed"), std::string::npos) << error;
}

}  // namespace
}  // namespace swlio::drivers::bag
