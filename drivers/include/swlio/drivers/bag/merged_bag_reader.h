#pragma once
/// @file
/// Several bag files read as one (a split rosbag2 bag: `<name>_0.db3`, `<name>_1.db3`, …):
/// topics of the same name and type become one, and messages are merged by receive time
/// (ties: the earlier file first). Each file keeps its own reader; the merge holds one pending
/// message per file, so a returned message stays valid until the next Next().

#include <memory>
#include <string>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"

namespace swlio::drivers::bag {

class MergedBagReader final : public BagReader {
 public:
  /// `parts` in recording order (at least one); `path` names the whole (the folder).
  MergedBagReader(std::string path, std::vector<std::unique_ptr<BagReader>> parts);

  std::string StorageDescription() const override;
  const std::vector<BagTopic>& topics() const override { return topics_; }
  bool Next(BagMessage* message) override;
  const std::string& error() const override { return error_; }
  const std::vector<std::string>& warnings() const override;
  uint64_t warnings_dropped() const override;
  const BagReadStats& stats() const override;
  const std::string& path() const override { return path_; }

 private:
  struct Part {
    std::unique_ptr<BagReader> reader;
    std::vector<uint32_t> topic_map;  ///< the part's topic → merged topic
    BagMessage pending;
    enum class State : uint8_t { kNeedsRead, kPending, kDone } state = State::kNeedsRead;
  };
  void MergeTopics(Part& part);
  /// Makes sure `part` holds its next message (if any); false on a read error.
  bool Fill(Part& part);

  std::string path_;
  std::vector<Part> parts_;
  std::vector<BagTopic> topics_;
  std::vector<uint64_t> next_index_;
  std::string error_;
  mutable std::vector<std::string> warnings_;
  mutable BagReadStats stats_;
};

}  // namespace swlio::drivers::bag
