#pragma once
/// @file
/// What `swlio-bag info` reports about a bag: per topic its type, what swlio reads it as, its
/// count and receive-time span, and — after decoding every message of a known type — how many
/// fail to decode and how many header stamps go backwards or repeat.

#include <cstdint>
#include <string>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/bag/ros_messages.h"

namespace swlio::tools {

struct TopicSummary {
  drivers::bag::BagTopic topic;
  drivers::bag::RosMessageKind kind = drivers::bag::RosMessageKind::kUnknown;
  uint64_t bytes = 0;
  uint64_t decode_errors = 0;
  uint64_t out_of_order = 0;  ///< header.stamp before the previous message's
  uint64_t duplicates = 0;    ///< header.stamp equal to the previous message's
  uint64_t packets = 0;       ///< LiDAR packets in packet messages
  std::string first_error;    ///< the first decode error, with its message index
};

struct BagSummary {
  std::string path;
  std::string storage;
  std::vector<TopicSummary> topics;
  uint64_t messages = 0;
  uint64_t bytes = 0;
  int64_t start_ns = 0;
  int64_t end_ns = 0;
  std::vector<std::string> reader_warnings;
  uint64_t reader_warnings_dropped = 0;
  std::string read_error;  ///< reading stopped early
};

/// Reads the whole bag; with `decode`, decodes every message of a known type.
BagSummary Summarize(drivers::bag::BagReader& reader, bool decode);

/// The report `swlio-bag info` prints.
std::string FormatSummary(const BagSummary& s);

}  // namespace swlio::tools
