#pragma once
/// @file
/// The container-independent view of a ROS bag: its topics and its messages in receive-time
/// order, each still serialized (CDR for ROS 2, ROS 1 serialization for ROS 1 bags).
///
/// Implementations: rosbag2 SQLite3 (`rosbag2_sqlite_reader.h`), MCAP (`mcap_reader.h`) and
/// ROS 1 bag v2.0 (`ros1_bag_reader.h`); `OpenBag()` (`bag_open.h`) picks one from the file.
/// Decoding the bytes into typed messages is `bag_message_decoder.h`'s job.
///
/// Damaged input never crashes a reader. What makes a whole file unreadable (not a bag, an
/// unknown version, a truncated header) fails `Open` with an error naming the file. Damage
/// further in (a chunk with a wrong CRC, a record cut short, a message of an unknown topic)
/// is skipped, counted in `BagReadStats` and described in `warnings()`, and the rest is read.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace swlio::drivers::bag {

/// How a topic's messages are serialized.
enum class MessageEncoding : uint8_t {
  kCdr,      ///< ROS 2: 4-byte encapsulation header + XCDR1 (rosbag2 "cdr", MCAP "cdr")
  kRos1,     ///< ROS 1 serialization (ROS 1 bags, MCAP "ros1")
  kUnknown,  ///< anything else; such messages are listed but not decoded
};

/// "cdr" → kCdr, "ros1" → kRos1, anything else → kUnknown.
MessageEncoding EncodingFromName(std::string_view name);

/// One topic of a bag (one MCAP channel, one ROS 1 connection, one rosbag2 topic row).
struct BagTopic {
  std::string name;           ///< e.g. "/rslidar_packets"
  std::string type;           ///< as stored: "sensor_msgs/msg/Imu" or "sensor_msgs/Imu"
  std::string encoding_name;  ///< as stored: "cdr", "ros1", …
  MessageEncoding encoding = MessageEncoding::kUnknown;
  std::string definition;           ///< message definition text when stored, else empty
  std::string definition_encoding;  ///< "ros2msg", "ros2idl", "ros1msg" or empty
  std::string md5sum;               ///< ROS 1 only
  uint64_t message_count = 0;       ///< messages of this topic the reader will return
  int64_t first_log_time_ns = 0;    ///< receive time of the first one (0 when none)
  int64_t last_log_time_ns = 0;     ///< receive time of the last one (0 when none)
};

/// One serialized message.
struct BagMessage {
  uint32_t topic = 0;  ///< index into BagReader::topics()
  uint64_t index =
      0;  ///< 0-based position among its topic's messages in the file (skipped ones count)
  int64_t log_time_ns = 0;  ///< receive (recording) time, ns since the Unix epoch
  /// The serialized message; valid until the next call to Next() on the same reader.
  std::span<const uint8_t> data;
};

/// What a reader skipped. Every skip also adds a line to BagReader::warnings().
struct BagReadStats {
  uint64_t messages_returned = 0;
  uint64_t bytes_returned = 0;    ///< sum of BagMessage::data sizes
  uint64_t messages_skipped = 0;  ///< unknown topic, bad time, unreadable row or record
  uint64_t chunks_skipped = 0;    ///< wrong CRC, failed decompression, bad size
  uint64_t records_skipped = 0;   ///< unknown opcodes and misplaced records
  uint64_t crc_checked = 0;       ///< CRCs compared (chunks, data section, summary)
};

class BagReader {
 public:
  virtual ~BagReader() = default;

  /// "rosbag2 sqlite3 (db schema 3)", "mcap (profile ros2)", "ROS 1 bag v2.0", …
  virtual std::string StorageDescription() const = 0;
  /// Every topic, including ones without messages. Counts and spans: MCAP and ROS 1 count the
  /// messages Next() will return (damaged chunks are already left out); .db3 counts rows, so a
  /// row skipped while reading (stats().messages_skipped) is still in its topic's count.
  virtual const std::vector<BagTopic>& topics() const = 0;
  /// The next message in receive-time order (ties in file order). False at the end, or on an
  /// error that stops reading (then error() is non-empty).
  virtual bool Next(BagMessage* message) = 0;
  /// Non-empty once reading stopped on an error; names the file.
  virtual const std::string& error() const = 0;
  /// Damage that was skipped, one line each, naming the file (at most kMaxWarnings lines;
  /// `warnings_dropped()` counts the rest).
  virtual const std::vector<std::string>& warnings() const = 0;
  virtual uint64_t warnings_dropped() const = 0;
  virtual const BagReadStats& stats() const = 0;
  /// The path the reader was opened with (for messages).
  virtual const std::string& path() const = 0;

  static constexpr size_t kMaxWarnings = 100;
};

/// Limits that keep a damaged or hostile file from exhausting memory.
struct BagReadLimits {
  /// Largest decompressed chunk (MCAP, ROS 1) accepted; larger ones are skipped with a warning.
  uint64_t max_chunk_bytes = uint64_t{1} << 30;
  /// Largest single message accepted.
  uint64_t max_message_bytes = uint64_t{512} << 20;
};

}  // namespace swlio::drivers::bag
