// The MCAP reader on files from the MCAP writer (every compression, with and without summary,
// chunked or not), on a file laid out byte by byte here from the specification, and on damaged
// files: cut at every offset, wrong CRCs, an unknown compression, unknown opcodes, messages of
// undefined channels, sizes beyond the limits.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "bag_test_util.h"
#include "swlio/drivers/bag/crc32.h"
#include "swlio/drivers/bag/mcap_reader.h"
#include "swlio/drivers/bag/mcap_writer.h"
#include "swlio/drivers/bytes.h"

namespace swlio::drivers::bag {
namespace {

using Bytes = std::vector<uint8_t>;

struct Expected {
  std::string topic;
  int64_t log_time_ns;
  Bytes data;
};

/// Two channels; 60 messages written in a shuffled time order across several small chunks.
Bytes WriteSample(McapWriterOptions options, std::vector<Expected>* expected) {
  options.chunk_bytes = options.chunk_bytes == 0 ? 0 : 700;
  auto w = McapWriter::CreateInMemory(options);
  const uint16_t imu_schema = w->AddSchema("sensor_msgs/msg/Imu", "ros2msg", "# imu\n");
  const uint16_t imu =
      w->AddChannel(imu_schema, "/imu/data", "cdr", {{"offered_qos_profiles", ""}});
  const uint16_t pts = w->AddChannel(0, "/points", "cdr");
  std::vector<int64_t> times(60);
  for (size_t i = 0; i < times.size(); ++i) times[i] = 1'000'000 + 1000 * static_cast<int64_t>(i);
  std::mt19937 rng(7);
  std::shuffle(times.begin(), times.end(), rng);
  for (size_t i = 0; i < times.size(); ++i) {
    const bool is_imu = i % 3 != 0;
    Bytes data(8 + i, static_cast<uint8_t>(i));
    data[0] = 0;
    data[1] = 1;
    EXPECT_TRUE(w->Write(is_imu ? imu : pts, times[i], times[i] - 5, data));
    expected->push_back({is_imu ? "/imu/data" : "/points", times[i], data});
  }
  std::string error;
  EXPECT_TRUE(w->Close(&error)) << error;
  std::stable_sort(expected->begin(), expected->end(), [](const Expected& a, const Expected& b) {
    return a.log_time_ns < b.log_time_ns;
  });
  return w->bytes();
}

std::unique_ptr<McapReader> OpenBytes(const Bytes& b, std::string* error) {
  return McapReader::OpenBytes(b, "test.mcap", {}, error);
}

void ExpectMessages(McapReader& r, const std::vector<Expected>& expected) {
  const auto all = test::ReadAll(r);
  ASSERT_EQ(all.size(), expected.size());
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(r.topics()[all[i].topic].name, expected[i].topic) << i;
    EXPECT_EQ(all[i].log_time_ns, expected[i].log_time_ns) << i;
    EXPECT_EQ(all[i].data, expected[i].data) << i;
  }
  EXPECT_EQ(r.error(), "");
}

struct Variant {
  Compression compression;
  bool chunked;
  bool summary;
};

class McapRoundTrip : public ::testing::TestWithParam<Variant> {};

TEST_P(McapRoundTrip, ReadsEveryMessageInTimeOrderWithTopicsAndCounts) {
  McapWriterOptions o;
  o.compression = GetParam().compression;
  o.chunk_bytes = GetParam().chunked ? 1 : 0;
  o.summary = GetParam().summary;
  std::vector<Expected> expected;
  const Bytes file = WriteSample(o, &expected);
  std::string error;
  auto r = OpenBytes(file, &error);
  ASSERT_NE(r, nullptr) << error;
  EXPECT_TRUE(r->warnings().empty()) << r->warnings().front();
  EXPECT_EQ(r->has_summary(), GetParam().summary);
  EXPECT_EQ(r->header().profile, "ros2");
  ASSERT_EQ(r->topics().size(), 2u);
  EXPECT_EQ(r->topics()[0].name, "/imu/data");
  EXPECT_EQ(r->topics()[0].type, "sensor_msgs/msg/Imu");
  EXPECT_EQ(r->topics()[0].definition, "# imu\n");
  EXPECT_EQ(r->topics()[0].definition_encoding, "ros2msg");
  EXPECT_EQ(r->topics()[0].encoding, MessageEncoding::kCdr);
  EXPECT_EQ(r->topics()[0].message_count, 40u);
  EXPECT_EQ(r->topics()[1].message_count, 20u);
  EXPECT_EQ(r->topics()[1].type, "");  // schema id 0
  EXPECT_EQ(r->topics()[0].first_log_time_ns, 1'001'000);
  // CRCs checked: each chunk's (when chunked), the data section's, the summary's.
  EXPECT_GE(r->stats().crc_checked, GetParam().chunked ? 3u : 1u);
  ExpectMessages(*r, expected);
}

INSTANTIATE_TEST_SUITE_P(Variants,
                         McapRoundTrip,
                         ::testing::Values(Variant{Compression::kNone, true, true},
                                           Variant{Compression::kZstd, true, true},
                                           Variant{Compression::kLz4Frame, true, true},
                                           Variant{Compression::kZstd, true, false},
                                           Variant{Compression::kLz4Frame, true, false},
                                           Variant{Compression::kNone, false, true},
                                           Variant{Compression::kNone, false, false}));

/// The smallest valid file, laid out by hand from the specification: magic, Header("ros2", ""),
/// Channel 1 without schema, one Message, an unknown record (opcode 0x42), DataEnd(0),
/// Footer(0, 0, 0), magic.
Bytes HandLaidFile() {
  Bytes b(mcap::kMagic.begin(), mcap::kMagic.end());
  const auto record = [&b](uint8_t op, const Bytes& content) {
    b.push_back(op);
    for (int i = 0; i < 8; ++i) b.push_back(static_cast<uint8_t>(content.size() >> (8 * i)));
    b.insert(b.end(), content.begin(), content.end());
  };
  record(0x01, {4, 0, 0, 0, 'r', 'o', 's', '2', 0, 0, 0, 0});
  record(0x04, {1, 0, 0, 0, 2, 0, 0, 0, '/', 'x', 3, 0, 0, 0, 'c', 'd', 'r', 0, 0, 0, 0});
  record(0x05,
         {1, 0, 9, 0, 0,   0, 0x10, 0x27, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,  // t=10000
          0, 1, 0, 0, 0xAB});
  record(0x42, {1, 2, 3});
  record(0x0F, {0, 0, 0, 0});
  record(0x02, Bytes(20, 0));
  b.insert(b.end(), mcap::kMagic.begin(), mcap::kMagic.end());
  return b;
}

TEST(McapReader, ReadsAHandLaidFileAndSkipsUnknownOpcodes) {
  std::string error;
  auto r = OpenBytes(HandLaidFile(), &error);
  ASSERT_NE(r, nullptr) << error;
  ASSERT_EQ(r->topics().size(), 1u);
  EXPECT_EQ(r->topics()[0].name, "/x");
  EXPECT_EQ(r->stats().records_skipped, 1u);
  const auto all = test::ReadAll(*r);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].log_time_ns, 10000);
  EXPECT_EQ(all[0].data, (Bytes{0, 1, 0, 0, 0xAB}));
  EXPECT_TRUE(r->warnings().empty());
}

TEST(McapReader, RefusesFilesThatAreNotMcap) {
  std::string error;
  EXPECT_EQ(OpenBytes({}, &error), nullptr);
  EXPECT_NE(error.find("test.mcap"), std::string::npos);
  const std::string ros1 = "#ROSBAG V2.0\n";
  EXPECT_EQ(OpenBytes(Bytes(ros1.begin(), ros1.end()), &error), nullptr);
  Bytes only_magic(mcap::kMagic.begin(), mcap::kMagic.end());
  EXPECT_EQ(OpenBytes(only_magic, &error), nullptr);
  EXPECT_NE(error.find("Header"), std::string::npos) << error;
  EXPECT_EQ(McapReader::Open("/nonexistent.mcap", {}, &error), nullptr);
  EXPECT_NE(error.find("/nonexistent.mcap"), std::string::npos);
}

TEST(McapReader, EveryCutReadsACorrectPrefixOrFailsClearly) {
  McapWriterOptions o;
  o.compression = Compression::kZstd;
  std::vector<Expected> expected;
  const Bytes file = WriteSample(o, &expected);
  size_t data_end = 0;  // where the DataEnd record starts: cuts after it keep every message
  for (size_t at = file.size() - 8 - 29; at > 0; --at) {
    if (file[at] == mcap::kDataEnd && bytes::ReadU64Le(&file[at + 1]) == 4) {
      data_end = at;
      break;
    }
  }
  ASSERT_GT(data_end, 0u);
  for (size_t n = 0; n < file.size(); ++n) {
    const Bytes cut(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(n));
    std::string error;
    auto r = OpenBytes(cut, &error);
    if (r == nullptr) {
      EXPECT_NE(error.find("test.mcap"), std::string::npos) << n;
      continue;
    }
    EXPECT_FALSE(r->warnings().empty()) << "no warning for a file cut at " << n;
    const auto all = test::ReadAll(*r);
    EXPECT_EQ(r->error(), "");
    if (n > data_end) {
      EXPECT_EQ(all.size(), expected.size()) << n;
    }
    for (const auto& m : all) {  // each message is one of the file's, intact
      const auto same = [&](const Expected& e) {
        return e.log_time_ns == m.log_time_ns && e.data == m.data &&
               e.topic == r->topics()[m.topic].name;
      };
      ASSERT_TRUE(std::any_of(expected.begin(), expected.end(), same)) << "cut at " << n;
    }
  }
}

/// Offset of the first Chunk record's content.
size_t FirstChunk(const Bytes& file) {
  size_t pos = 8;
  while (pos + 9 <= file.size() && file[pos] != mcap::kChunk) {
    pos += 9 + bytes::ReadU64Le(&file[pos + 1]);
  }
  return pos + 9;
}

TEST(McapReader, AChunkWithAWrongCrcIsSkippedWithAWarning) {
  McapWriterOptions o;
  o.compression = Compression::kNone;
  std::vector<Expected> expected;
  Bytes file = WriteSample(o, &expected);
  const size_t chunk = FirstChunk(file);
  // Chunk header: times 16, size 8, crc 4, compression "" 4, records length 8: records at +40.
  file[chunk + 40 + 30] ^= 0xFF;  // inside the first message's data
  std::string error;
  auto r = OpenBytes(file, &error);
  ASSERT_NE(r, nullptr) << error;
  EXPECT_EQ(r->stats().chunks_skipped, 1u);
  ASSERT_FALSE(r->warnings().empty());
  EXPECT_NE(r->warnings()[0].find("chunk skipped: CRC"), std::string::npos) << r->warnings()[0];
  EXPECT_NE(r->warnings()[0].find("test.mcap: byte"), std::string::npos);
  const auto all = test::ReadAll(*r);
  EXPECT_GT(all.size(), 0u);
  EXPECT_LT(all.size(), expected.size());
}

TEST(McapReader, ADamagedCompressedChunkIsSkipped) {
  for (const Compression c : {Compression::kZstd, Compression::kLz4Frame}) {
    McapWriterOptions o;
    o.compression = c;
    std::vector<Expected> expected;
    Bytes file = WriteSample(o, &expected);
    const size_t chunk = FirstChunk(file);
    const size_t records = chunk + 16 + 8 + 4 + 4 + (c == Compression::kZstd ? 4 : 3) + 8;
    file[records + 12] ^= 0x5A;
    std::string error;
    auto r = OpenBytes(file, &error);
    ASSERT_NE(r, nullptr) << error;
    EXPECT_EQ(r->stats().chunks_skipped, 1u);
    EXPECT_LT(test::ReadAll(*r).size(), expected.size());
  }
}

TEST(McapReader, AnUnknownCompressionSkipsTheChunk) {
  McapWriterOptions o;
  o.compression = Compression::kZstd;
  std::vector<Expected> expected;
  Bytes file = WriteSample(o, &expected);
  const size_t name = FirstChunk(file) + 16 + 8 + 4 + 4;
  ASSERT_EQ(std::string(&file[name], &file[name] + 4), "zstd");
  file[name + 3] = 'X';
  std::string error;
  auto r = OpenBytes(file, &error);
  ASSERT_NE(r, nullptr) << error;
  EXPECT_EQ(r->stats().chunks_skipped, 1u);
  EXPECT_NE(r->warnings()[0].find("unknown compression 'zstX'"), std::string::npos);
}

TEST(McapReader, DataSectionCrcMismatchIsAWarning) {
  McapWriterOptions o;
  o.compression = Compression::kZstd;
  std::vector<Expected> expected;
  Bytes file = WriteSample(o, &expected);
  file[8 + 9 + 4] ^= 1;  // the Header's profile text: only the data-section CRC covers it
  std::string error;
  auto r = OpenBytes(file, &error);
  ASSERT_NE(r, nullptr) << error;
  ASSERT_EQ(r->warnings().size(), 1u);
  EXPECT_NE(r->warnings()[0].find("data section CRC"), std::string::npos);
  EXPECT_EQ(test::ReadAll(*r).size(), expected.size());
}

TEST(McapReader, SummaryCrcMismatchLeavesTheSummaryUnused) {
  McapWriterOptions o;
  std::vector<Expected> expected;
  Bytes file = WriteSample(o, &expected);
  file[file.size() - 8 - 29 - 3] ^= 1;  // inside the last SummaryOffset record
  std::string error;
  auto r = OpenBytes(file, &error);
  ASSERT_NE(r, nullptr) << error;
  ASSERT_EQ(r->warnings().size(), 1u);
  EXPECT_NE(r->warnings()[0].find("summary CRC"), std::string::npos);
  EXPECT_EQ(test::ReadAll(*r).size(), expected.size());
}

TEST(McapReader, MessagesOfUndefinedChannelsAreCountedAndSkipped) {
  Bytes file = HandLaidFile();
  // The Channel record starts after magic (8) and the Header record (9 + 12): id 1 → 3.
  file[8 + 21 + 9] = 3;
  std::string error;
  auto r = OpenBytes(file, &error);
  ASSERT_NE(r, nullptr) << error;
  EXPECT_EQ(r->stats().messages_skipped, 1u);
  EXPECT_NE(r->warnings()[0].find("channel/connection 1"), std::string::npos);
  EXPECT_TRUE(test::ReadAll(*r).empty());
}

TEST(McapReader, ChunkSizesOverTheLimitAreSkipped) {
  McapWriterOptions o;
  std::vector<Expected> expected;
  const Bytes file = WriteSample(o, &expected);
  BagReadLimits limits;
  limits.max_chunk_bytes = 100;  // every chunk of the sample is larger
  std::string error;
  auto r = McapReader::OpenBytes(file, "small-limit", limits, &error);
  ASSERT_NE(r, nullptr) << error;
  EXPECT_GT(r->stats().chunks_skipped, 0u);
  EXPECT_NE(r->warnings()[0].find("over the limit"), std::string::npos);
  // Statistics in the summary disagree with what could be read: reported.
  EXPECT_NE(r->warnings().back().find("Statistics count 60"), std::string::npos);
}

TEST(McapWriter, FileLayoutFollowsTheSpecification) {
  McapWriterOptions o;
  o.compression = Compression::kNone;
  std::vector<Expected> expected;
  const Bytes file = WriteSample(o, &expected);
  ASSERT_TRUE(std::equal(mcap::kMagic.begin(), mcap::kMagic.end(), file.begin()));
  ASSERT_TRUE(std::equal(mcap::kMagic.begin(), mcap::kMagic.end(), file.end() - 8));
  EXPECT_EQ(file[8], mcap::kHeader);
  const size_t footer = file.size() - 8 - 29;
  EXPECT_EQ(file[footer], mcap::kFooter);
  const uint64_t summary_start = bytes::ReadU64Le(&file[footer + 9]);
  const uint64_t offsets_start = bytes::ReadU64Le(&file[footer + 17]);
  const uint32_t crc = bytes::ReadU32Le(&file[footer + 25]);
  ASSERT_GT(summary_start, 0u);
  EXPECT_EQ(file[summary_start], mcap::kSchema);
  EXPECT_EQ(file[offsets_start], mcap::kSummaryOffset);
  const std::span<const uint8_t> covered(&file[summary_start], footer + 9 + 16 - summary_start);
  EXPECT_EQ(Crc32(covered), crc);
  // DataEnd directly before the summary; its CRC covers everything before it.
  const size_t data_end = summary_start - 13;
  EXPECT_EQ(file[data_end], mcap::kDataEnd);
  EXPECT_EQ(Crc32(std::span(file).first(data_end)), bytes::ReadU32Le(&file[data_end + 9]));
}

}  // namespace
}  // namespace swlio::drivers::bag
