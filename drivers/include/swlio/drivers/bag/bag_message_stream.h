#pragma once
/// @file
/// A bag as swlio's input: the messages of the selected topics (topic_selection.h), decoded,
/// in receive-time order — what swlio-run, swlio-replay and the export read.
///
/// Bad messages never stop the stream; each is skipped, counted per topic and described (file,
/// topic, message index) in warnings():
///   - bytes that do not match the declared type (decode error);
///   - header.stamp ≤ 0, earlier than the previous message's on the topic (out of order), or
///     equal to it (duplicate) — checked on every message that has a header;
///   - packet messages without packets, clouds without a finite point (empty);
///   - NaN or infinite points are dropped from clouds and counted.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/bag/message_decoder.h"
#include "swlio/drivers/bag/point_cloud_points.h"
#include "swlio/drivers/bag/topic_selection.h"
#include "swlio/drivers/bag/warning_log.h"

namespace swlio::drivers::bag {

struct BagStreamOptions {
  TopicChoice topics;
  CloudOptions cloud;
};

/// What happened to one topic's messages.
struct TopicStreamStats {
  uint64_t delivered = 0;
  uint64_t decode_errors = 0;
  uint64_t bad_stamps = 0;    ///< header.stamp ≤ 0
  uint64_t out_of_order = 0;  ///< header.stamp before the previous one
  uint64_t duplicates = 0;    ///< header.stamp equal to the previous one
  uint64_t empty = 0;         ///< no packets, or no finite point
  uint64_t non_finite_points = 0;
  uint64_t skipped() const {
    return decode_errors + bad_stamps + out_of_order + duplicates + empty;
  }
};

/// One delivered message; the pointers stay valid until the next Next().
struct StreamMessage {
  TopicRole role = TopicRole::kNone;
  RosMessageKind kind = RosMessageKind::kUnknown;
  uint32_t topic = 0;
  uint64_t index = 0;       ///< the message's index in its topic
  int64_t log_time_ns = 0;  ///< receive time
  const DecodedMessage* decoded = nullptr;
  const CloudPoints* cloud = nullptr;  ///< PointCloud2 only: its points with times
};

class BagMessageStream {
 public:
  /// Selects topics on `reader`'s list. False (nullptr) with `error` as SelectTopics says.
  static std::unique_ptr<BagMessageStream> Create(std::unique_ptr<BagReader> reader,
                                                  const BagStreamOptions& options,
                                                  std::string* error);

  /// The next good message of a selected topic; false at the end or on a read error
  /// (`reader().error()`).
  bool Next(StreamMessage* out);

  const BagReader& reader() const { return *reader_; }
  const SelectedTopics& selected() const { return selected_; }
  const TopicStreamStats& topic_stats(uint32_t topic) const { return stats_[topic]; }
  const std::vector<std::string>& warnings() const { return warnings_.lines(); }
  uint64_t warnings_dropped() const { return warnings_.dropped(); }

 private:
  BagMessageStream(std::unique_ptr<BagReader> reader, const BagStreamOptions& options);
  /// Decodes and checks one message; false when it is skipped (counted, warned).
  bool Accept(const BagMessage& m, StreamMessage* out);
  bool CheckStamp(const BagMessage& m, TopicStreamStats& s);
  void Skip(const BagMessage& m, const std::string& why);

  std::unique_ptr<BagReader> reader_;
  BagStreamOptions options_;
  SelectedTopics selected_;
  std::vector<RosMessageKind> kinds_;
  std::vector<TopicRole> roles_;  ///< kNone for topics not selected
  std::vector<TopicStreamStats> stats_;
  std::vector<int64_t> last_stamp_ns_;
  DecodedMessage decoded_;
  CloudPoints cloud_;
  WarningLog warnings_{BagReader::kMaxWarnings};
};

}  // namespace swlio::drivers::bag
