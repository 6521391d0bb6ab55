// The rosbag2 SQLite3 reader on files written here in each database schema version, and on
// damaged ones: rows of unknown topics or without a BLOB, files that are not databases or not
// rosbag2 databases, a view where the messages table should be, cut files, per-message zstd.

#include <gtest/gtest.h>
#include <zstd.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bag_test_util.h"
#include "db3_builder.h"
#include "swlio/drivers/bag/rosbag2_sqlite_reader.h"
#include "test_data.h"

namespace swlio::drivers::bag {
namespace {

using test::Db3Message;
using test::Db3Topic;

std::vector<Db3Topic> TwoTopics() {
  return {{3, "/imu/data", "sensor_msgs/msg/Imu", "cdr", "std_msgs/Header header\n..."},
          {7, "/points", "sensor_msgs/msg/PointCloud2", "cdr", ""}};
}

/// Out of time order on purpose, with a tie (t = 20) that keeps insertion order.
std::vector<Db3Message> SomeMessages() {
  return {{3, 30, {0, 1, 0, 0, 3}},
          {7, 20, {0, 1, 0, 0, 2}},
          {3, 10, {0, 1, 0, 0, 1}},
          {3, 20, {0, 1, 0, 0, 4}}};
}

std::unique_ptr<Rosbag2SqliteReader> Open(const std::filesystem::path& p, std::string* error) {
  return Rosbag2SqliteReader::Open(p.string(), {}, error);
}

std::vector<uint8_t> FileBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Rosbag2SchemaVersions : public ::testing::TestWithParam<int> {};

TEST_P(Rosbag2SchemaVersions, ReadsTopicsCountsAndMessagesInTimeOrder) {
  const int version = GetParam();
  const auto path = test::MakeTempDir("db3") / "bag_0.db3";
  test::WriteDb3(path, version, TwoTopics(), SomeMessages());
  std::string error;
  auto reader = Open(path, &error);
  ASSERT_NE(reader, nullptr) << error;
  EXPECT_EQ(reader->db_schema_version(), version);
  ASSERT_EQ(reader->topics().size(), 2u);
  const BagTopic& imu = reader->topics()[0];
  EXPECT_EQ(imu.name, "/imu/data");
  EXPECT_EQ(imu.message_count, 3u);
  EXPECT_EQ(imu.first_log_time_ns, 10);
  EXPECT_EQ(imu.last_log_time_ns, 30);
  EXPECT_EQ(imu.definition.empty(), version < 4);
  EXPECT_EQ(reader->topics()[1].message_count, 1u);
  const auto all = test::ReadAll(*reader);
  ASSERT_EQ(all.size(), 4u);
  const std::vector<uint8_t> order = {1, 2, 4, 3};  // by time, the tie in insertion order
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(all[i].data.back(), order[i]) << i;
  EXPECT_EQ(all[0].index, 0u);  // first /imu/data message
  EXPECT_EQ(all[2].index, 1u);  // second /imu/data message
  EXPECT_EQ(all[1].topic, 1u);
  EXPECT_EQ(reader->error(), "");
  EXPECT_NE(reader->StorageDescription().find("db schema " + std::to_string(version)),
            std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(AllVersions, Rosbag2SchemaVersions, ::testing::Values(1, 2, 3, 4));

TEST(Rosbag2SqliteReader, SkipsAndCountsRowsOfUnknownTopicsAndNonBlobData) {
  const auto path = test::MakeTempDir("db3") / "bad_rows.db3";
  test::WriteDb3(path, 3, TwoTopics(), {{3, 1, {0, 1, 0, 0}}, {99, 2, {1}}, {7, 3, {0, 1, 0, 0}}});
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    test::Db3Exec(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(3, 4, 'text')");
    sqlite3_close(db);
  }
  std::string error;
  auto reader = Open(path, &error);
  ASSERT_NE(reader, nullptr) << error;
  const auto all = test::ReadAll(*reader);
  EXPECT_EQ(all.size(), 2u);
  EXPECT_EQ(reader->stats().messages_skipped, 2u);
  ASSERT_EQ(reader->warnings().size(), 2u);
  EXPECT_NE(reader->warnings()[0].find("unknown topic_id 99"), std::string::npos);
  EXPECT_NE(reader->warnings()[1].find("/imu/data #1"), std::string::npos);
  EXPECT_NE(reader->warnings()[1].find("not a BLOB"), std::string::npos);
  EXPECT_NE(reader->warnings()[1].find(path.string()), std::string::npos);
}

TEST(Rosbag2SqliteReader, KeepsTimeOrderWhateverTheFileHolds) {
  const auto path = test::MakeTempDir("db3") / "times.db3";
  test::WriteDb3(path, 3, TwoTopics(), {{3, 10, {0, 1, 0, 0}}, {3, 20, {0, 1, 0, 0}}});
  {
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
    // A text timestamp sorts after every integer (SQLite's type order).
    test::Db3Exec(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(3, 'late', x'00')");
    sqlite3_close(db);
  }
  std::string error;
  auto reader = Open(path, &error);
  ASSERT_NE(reader, nullptr) << error;
  const auto all = test::ReadAll(*reader);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].log_time_ns, 10);
  EXPECT_EQ(all[1].log_time_ns, 20);
  ASSERT_EQ(reader->warnings().size(), 1u);
  EXPECT_NE(reader->warnings()[0].find("timestamp is not an integer"), std::string::npos);
}

TEST(Rosbag2SqliteReader, RefusesFilesThatAreNotRosbag2Databases) {
  const auto dir = test::MakeTempDir("db3");
  std::string error;
  EXPECT_EQ(Open(dir / "missing.db3", &error), nullptr);
  EXPECT_NE(error.find("missing.db3"), std::string::npos) << error;
  std::ofstream(dir / "text.db3") << "this is not a database, only a line of text\n";
  error.clear();
  EXPECT_EQ(Open(dir / "text.db3", &error), nullptr);
  EXPECT_NE(error.find("text.db3"), std::string::npos) << error;
  std::ofstream(dir / "empty.db3").close();
  error.clear();
  EXPECT_EQ(Open(dir / "empty.db3", &error), nullptr);  // an empty file is an empty database
  EXPECT_NE(error.find("not a rosbag2 database"), std::string::npos) << error;
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir / "other.db3").c_str(), &db), SQLITE_OK);
  test::Db3Exec(db, "CREATE TABLE things(a)");
  sqlite3_close(db);
  error.clear();
  EXPECT_EQ(Open(dir / "other.db3", &error), nullptr);
  EXPECT_NE(error.find("not a rosbag2 database"), std::string::npos) << error;
}

TEST(Rosbag2SqliteReader, RefusesAViewInPlaceOfTheMessagesTable) {
  const auto path = test::MakeTempDir("db3") / "view.db3";
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  test::Db3Exec(db, test::Db3TopicsTable(1));
  // A view that never ends, which a crafted file could offer as 'messages'.
  test::Db3Exec(db,
                "CREATE VIEW messages AS WITH RECURSIVE c(x) AS (SELECT 1 UNION ALL SELECT x+1 "
                "FROM c) SELECT x AS id, 1 AS topic_id, x AS timestamp, x'00' AS data FROM c");
  sqlite3_close(db);
  std::string error;
  EXPECT_EQ(Open(path, &error), nullptr);
  EXPECT_NE(error.find("not a rosbag2 database"), std::string::npos) << error;
}

TEST(Rosbag2SqliteReader, InMemoryImageReadsLikeTheFile) {
  const auto path = test::MakeTempDir("db3") / "bag.db3";
  test::WriteDb3(path, 4, TwoTopics(), SomeMessages());
  const std::vector<uint8_t> image = FileBytes(path);
  std::string error;
  auto from_file = Open(path, &error);
  auto from_bytes = Rosbag2SqliteReader::OpenBytes(image, "image", {}, &error);
  ASSERT_NE(from_file, nullptr);
  ASSERT_NE(from_bytes, nullptr) << error;
  EXPECT_EQ(test::ReadAll(*from_file), test::ReadAll(*from_bytes));
}

TEST(Rosbag2SqliteReader, CutFilesFailOrReadLessNeverCrash) {
  SWLIO_REQUIRE_DATA(real, "rs16_washing_house/rosbag2_2022_08_16-11_55_30_0.db3");
  const std::vector<uint8_t> image = FileBytes(real);
  size_t opened = 0;
  for (size_t n = 0; n < image.size(); n += 4093) {
    std::string error;
    auto reader = Rosbag2SqliteReader::OpenBytes(std::span(image).first(n), "cut", {}, &error);
    if (reader == nullptr) {
      EXPECT_NE(error.find("cut"), std::string::npos) << error;
      continue;
    }
    ++opened;
    const auto all = test::ReadAll(*reader);
    EXPECT_LE(all.size(), 80u);
    if (all.size() < 80u) {
      EXPECT_FALSE(reader->error().empty()) << "cut at " << n;
    }
  }
  std::string error;
  auto whole = Rosbag2SqliteReader::OpenBytes(image, "whole", {}, &error);
  ASSERT_NE(whole, nullptr) << error;
  EXPECT_EQ(test::ReadAll(*whole).size(), 80u);
  RecordProperty("cut_images_opened", static_cast<int>(opened));
}

TEST(Rosbag2SqliteReader, UndoesPerMessageZstdWhenAsked) {
  const std::vector<uint8_t> cdr = {0, 1, 0, 0, 42, 43, 44, 45};
  std::vector<uint8_t> z(ZSTD_compressBound(cdr.size()));
  z.resize(ZSTD_compress(z.data(), z.size(), cdr.data(), cdr.size(), 3));
  const auto path = test::MakeTempDir("db3") / "zstd.db3";
  test::WriteDb3(path, 3, TwoTopics(), {{3, 1, z}, {3, 2, {1, 2, 3}}});
  Rosbag2SqliteOptions options;
  options.zstd_per_message = true;
  std::string error;
  auto reader = Rosbag2SqliteReader::Open(path.string(), options, &error);
  ASSERT_NE(reader, nullptr) << error;
  const auto all = test::ReadAll(*reader);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].data, cdr);
  EXPECT_EQ(reader->stats().messages_skipped, 1u);  // {1, 2, 3} is no zstd frame
}

}  // namespace
}  // namespace swlio::drivers::bag
