// Several bag files merged by receive time (merged_bag_reader.h).

#include "swlio/drivers/bag/merged_bag_reader.h"

#include <algorithm>

namespace swlio::drivers::bag {

MergedBagReader::MergedBagReader(std::string path, std::vector<std::unique_ptr<BagReader>> parts)
    : path_(std::move(path)) {
  for (auto& reader : parts) {
    parts_.push_back({std::move(reader), {}, {}, Part::State::kNeedsRead});
    MergeTopics(parts_.back());
  }
  next_index_.assign(topics_.size(), 0);
}

void MergedBagReader::MergeTopics(Part& part) {
  for (const BagTopic& t : part.reader->topics()) {
    const auto same = [&t](const BagTopic& m) { return m.name == t.name && m.type == t.type; };
    auto it = std::find_if(topics_.begin(), topics_.end(), same);
    if (it == topics_.end()) {
      topics_.push_back(t);
      topics_.back().message_count = 0;
      it = topics_.end() - 1;
    }
    BagTopic& m = *it;
    if (t.message_count > 0) {
      m.first_log_time_ns = m.message_count == 0
                                ? t.first_log_time_ns
                                : std::min(m.first_log_time_ns, t.first_log_time_ns);
      m.last_log_time_ns = std::max(m.message_count == 0 ? t.last_log_time_ns : m.last_log_time_ns,
                                    t.last_log_time_ns);
    }
    m.message_count += t.message_count;
    if (m.definition.empty()) m.definition = t.definition;
    part.topic_map.push_back(static_cast<uint32_t>(it - topics_.begin()));
  }
}

std::string MergedBagReader::StorageDescription() const {
  return parts_.front().reader->StorageDescription() + ", " + std::to_string(parts_.size()) +
         " files";
}

bool MergedBagReader::Fill(Part& part) {
  if (part.state != Part::State::kNeedsRead) return true;
  if (part.reader->Next(&part.pending)) {
    part.state = Part::State::kPending;
    return true;
  }
  part.state = Part::State::kDone;
  if (part.reader->error().empty()) return true;
  error_ = part.reader->error();
  return false;
}

bool MergedBagReader::Next(BagMessage* message) {
  if (!error_.empty()) return false;
  Part* best = nullptr;
  for (Part& part : parts_) {
    if (!Fill(part)) return false;
    if (part.state != Part::State::kPending) continue;
    if (best == nullptr || part.pending.log_time_ns < best->pending.log_time_ns) best = &part;
  }
  if (best == nullptr) return false;
  *message = best->pending;
  message->topic = best->topic_map[best->pending.topic];
  message->index = next_index_[message->topic]++;
  // Read on from this part only on the next call, when the caller is done with `message`.
  best->state = Part::State::kNeedsRead;
  return true;
}

const std::vector<std::string>& MergedBagReader::warnings() const {
  warnings_.clear();
  for (const Part& p : parts_) {
    warnings_.insert(warnings_.end(), p.reader->warnings().begin(), p.reader->warnings().end());
  }
  return warnings_;
}

uint64_t MergedBagReader::warnings_dropped() const {
  uint64_t n = 0;
  for (const Part& p : parts_) n += p.reader->warnings_dropped();
  return n;
}

const BagReadStats& MergedBagReader::stats() const {
  stats_ = {};
  for (const Part& p : parts_) {
    const BagReadStats& s = p.reader->stats();
    stats_.messages_returned += s.messages_returned;
    stats_.bytes_returned += s.bytes_returned;
    stats_.messages_skipped += s.messages_skipped;
    stats_.chunks_skipped += s.chunks_skipped;
    stats_.records_skipped += s.records_skipped;
    stats_.crc_checked += s.crc_checked;
  }
  return stats_;
}

}  // namespace swlio::drivers::bag
