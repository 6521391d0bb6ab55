#pragma once
/// @file
/// MCAP records, as the specification defines them (foxglove/mcap 95d0673
/// website/docs/spec/index.md; research/bags.md §3):
///
///   file    = magic, Header, data section, [summary], [summary offsets], Footer, magic
///   magic   = 89 4D 43 41 50 30 0D 0A ("\x89MCAP0\r\n", major version '0')
///   record  = opcode u8 | content length u64 | content
///
/// All integers little-endian; String = u32 byte length + UTF-8; Bytes = raw to the end of the
/// field; Array and Map = u32 *byte* length + entries; Timestamp = u64 ns. Records may gain
/// trailing fields: parsers read the fields they know and ignore the rest of the content.
/// Opcode 0x00 is reserved, 0x80–0xFF are private (skipped like every unknown opcode).

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace swlio::drivers::bag::mcap {

inline constexpr std::array<uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
inline constexpr size_t kRecordPrefixBytes = 9;    ///< opcode + content length
inline constexpr size_t kMessageHeaderBytes = 22;  ///< channel 2, sequence 4, two times 8
inline constexpr size_t kFooterContentBytes = 20;  ///< two u64 offsets, u32 CRC

enum Opcode : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

struct Header {
  std::string profile;  ///< "ros2", "ros1", "" …
  std::string library;
};

struct Footer {
  uint64_t summary_start = 0;         ///< 0: no summary section
  uint64_t summary_offset_start = 0;  ///< 0: no summary offset section
  uint32_t summary_crc = 0;           ///< 0: not computed
};

struct Schema {
  uint16_t id = 0;  ///< 0 is invalid
  std::string name;
  std::string encoding;
  std::string data;
  bool operator==(const Schema&) const = default;
};

struct Channel {
  uint16_t id = 0;
  uint16_t schema_id = 0;  ///< 0: no schema
  std::string topic;
  std::string message_encoding;
  std::map<std::string, std::string> metadata;
  bool operator==(const Channel&) const = default;
};

/// A Message record's header; `data` views the rest of the content.
struct Message {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0;
  uint64_t publish_time = 0;
  std::span<const uint8_t> data;
};

/// A Chunk record; `records` views the (compressed) records.
struct Chunk {
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  uint64_t uncompressed_size = 0;
  uint32_t uncompressed_crc = 0;  ///< 0: not computed
  std::string compression;        ///< "", "zstd", "lz4"
  std::span<const uint8_t> records;
};

/// The Statistics fields the reader checks its own counts against.
struct Statistics {
  uint64_t message_count = 0;
  std::map<uint16_t, uint64_t> channel_message_counts;
};

/// Each parser reads one record's content; false when a field does not fit in it.
bool ParseHeader(std::span<const uint8_t> content, Header* out);
bool ParseFooter(std::span<const uint8_t> content, Footer* out);
bool ParseSchema(std::span<const uint8_t> content, Schema* out);
bool ParseChannel(std::span<const uint8_t> content, Channel* out);
bool ParseMessage(std::span<const uint8_t> content, Message* out);
bool ParseChunk(std::span<const uint8_t> content, Chunk* out);
bool ParseStatistics(std::span<const uint8_t> content, Statistics* out);
bool ParseDataEnd(std::span<const uint8_t> content, uint32_t* data_section_crc);

/// Builds one record's content field by field (the writer's side).
class RecordBuilder {
 public:
  RecordBuilder& U8(uint8_t v);
  RecordBuilder& U16(uint16_t v);
  RecordBuilder& U32(uint32_t v);
  RecordBuilder& U64(uint64_t v);
  RecordBuilder& String(std::string_view s);
  RecordBuilder& Raw(std::span<const uint8_t> b);
  /// u32 byte length of a Map<String, String>, then its entries.
  RecordBuilder& StringMap(const std::map<std::string, std::string>& m);
  const std::vector<uint8_t>& content() const { return content_; }

 private:
  std::vector<uint8_t> content_;
};

/// opcode | u64 length | content, appended to `out`.
void AppendRecord(uint8_t opcode, std::span<const uint8_t> content, std::vector<uint8_t>* out);

}  // namespace swlio::drivers::bag::mcap
