#pragma once
/// @file
/// ROS 1 bag v2.0 records (ros/ros_comm 845f746 tools/rosbag_storage include/rosbag/constants.h,
/// src/bag.cpp; wiki.ros.org/Bags/Format/2.0; research/bags.md §4):
///
///   file   = "#ROSBAG V2.0\n", records
///   record = header_len u32 | header | data_len u32 | data
///   header = fields, each field_len u32 | name '=' value (field_len counts name, '=', value)
///
/// Values are binary little-endian (u32, u64; time = u32 sec + u32 nsec) or text. Every header
/// has `op` (1 byte): 0x02 message data {conn, time}, 0x03 bag header {index_pos, conn_count,
/// chunk_count}, 0x04 index data, 0x05 chunk {compression: none/bz2/lz4, size: uncompressed},
/// 0x06 chunk info, 0x07 connection {conn, topic; data: a second header with topic, type,
/// md5sum, message_definition, callerid, latching}.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace swlio::drivers::bag::ros1 {

inline constexpr std::string_view kVersionLine = "#ROSBAG V2.0\n";

enum Op : uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

/// The fields of one record header (views into the file or chunk).
class RecordHeader {
 public:
  /// Splits `bytes` into fields; false when a field length runs past the end or a field has
  /// no '='.
  bool Parse(std::span<const uint8_t> bytes);
  /// The value of `name`, if present.
  bool Find(std::string_view name, std::span<const uint8_t>* value) const;
  bool U8(std::string_view name, uint8_t* v) const;
  bool U32(std::string_view name, uint32_t* v) const;
  bool U64(std::string_view name, uint64_t* v) const;
  /// u32 sec + u32 nsec → ns; false when absent, of the wrong size, or nsec ≥ 10⁹.
  bool Time(std::string_view name, int64_t* t_ns) const;
  bool Text(std::string_view name, std::string* v) const;

 private:
  std::vector<std::pair<std::string_view, std::span<const uint8_t>>> fields_;
};

/// One record: its header fields' bytes and its data.
struct Record {
  std::span<const uint8_t> header;
  std::span<const uint8_t> data;
  size_t size = 0;  ///< bytes from the record's start to the next record
};

/// Reads the record at the start of `bytes`; false when its lengths run past the end.
bool ReadRecord(std::span<const uint8_t> bytes, Record* out);

/// Appends a record (header fields in the given order) to `out` (for writers).
void AppendRecord(const std::vector<std::pair<std::string, std::vector<uint8_t>>>& fields,
                  std::span<const uint8_t> data,
                  std::vector<uint8_t>* out);

}  // namespace swlio::drivers::bag::ros1
