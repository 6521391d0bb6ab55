#pragma once
/// @file
/// What every bag-container fuzz target checks after reading a whole input: the reader stops,
/// returns messages in nondecreasing receive time, only of listed topics, never more than the
/// topics' counts promise, and every message decodes or fails cleanly as its topic's kind.

#include <cstdint>
#include <string>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/bag/message_decoder.h"
#include "swlio/drivers/bag/point_cloud_points.h"

namespace swlio::fuzz {

inline void Check(bool ok) {
  if (!ok) __builtin_trap();
}

/// Reads `reader` to the end. `exact`: the topics' counts must equal what is returned (the
/// chunked readers index every message before returning any).
inline void ReadToEnd(drivers::bag::BagReader& reader, bool exact) {
  namespace bag = drivers::bag;
  uint64_t promised = 0;
  for (const bag::BagTopic& t : reader.topics()) promised += t.message_count;
  bag::BagMessage m;
  bag::DecodedMessage decoded;
  bag::CloudPoints cloud;
  std::string error;
  uint64_t n = 0;
  int64_t last = INT64_MIN;
  while (reader.Next(&m)) {
    Check(m.topic < reader.topics().size());
    Check(m.log_time_ns >= last);
    last = m.log_time_ns;
    ++n;
    const bag::BagTopic& t = reader.topics()[m.topic];
    if (!bag::DecodeMessage(bag::ClassifyTopic(t), t.encoding, m.data, &decoded, &error)) continue;
    if (decoded.kind == bag::RosMessageKind::kPointCloud2) {
      bag::CloudFromPointCloud2(decoded.cloud, {}, &cloud, &error);
    }
  }
  Check(n <= promised || !exact);
  if (exact) Check(n == promised || !reader.error().empty());
  Check(reader.stats().messages_returned == n);
}

/// Limits small enough that a hostile size field cannot exhaust the fuzzer's memory.
inline drivers::bag::BagReadLimits FuzzLimits() {
  drivers::bag::BagReadLimits l;
  l.max_chunk_bytes = 4u << 20;
  l.max_message_bytes = 4u << 20;
  return l;
}

}  // namespace swlio::fuzz
