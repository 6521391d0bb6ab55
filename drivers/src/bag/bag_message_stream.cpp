// Selected bag topics, decoded and checked, in receive-time order (bag_message_stream.h).

#include "swlio/drivers/bag/bag_message_stream.h"

#include <limits>

namespace swlio::drivers::bag {

BagMessageStream::BagMessageStream(std::unique_ptr<BagReader> reader,
                                   const BagStreamOptions& options)
    : reader_(std::move(reader)), options_(options) {}

std::unique_ptr<BagMessageStream> BagMessageStream::Create(std::unique_ptr<BagReader> reader,
                                                           const BagStreamOptions& options,
                                                           std::string* error) {
  if (!reader) {
    if (error->empty()) *error = "no bag";
    return nullptr;
  }
  std::unique_ptr<BagMessageStream> s(new BagMessageStream(std::move(reader), options));
  const std::vector<BagTopic>& topics = s->reader_->topics();
  if (!SelectTopics(topics, options.topics, &s->selected_, error)) {
    *error = s->reader_->path() + ": " + *error;
    return nullptr;
  }
  s->roles_.assign(topics.size(), TopicRole::kNone);
  for (uint32_t i = 0; i < topics.size(); ++i) s->kinds_.push_back(ClassifyTopic(topics[i]));
  const SelectedTopics& sel = s->selected_;
  for (const auto& t : {sel.lidar, sel.lidar_info, sel.imu, sel.gnss, sel.wheel}) {
    if (t) s->roles_[*t] = RoleOf(s->kinds_[*t]);
  }
  s->stats_.assign(topics.size(), {});
  s->last_stamp_ns_.assign(topics.size(), std::numeric_limits<int64_t>::min());
  return s;
}

void BagMessageStream::Skip(const BagMessage& m, const std::string& why) {
  warnings_.Add(reader_->path() + ": " + reader_->topics()[m.topic].name + " #" +
                std::to_string(m.index) + ": " + why + "; skipped");
}

bool BagMessageStream::CheckStamp(const BagMessage& m, TopicStreamStats& s) {
  const std::optional<int64_t> stamp = HeaderStamp(decoded_);
  if (!stamp) return true;
  int64_t& last = last_stamp_ns_[m.topic];
  if (*stamp <= 0) {
    ++s.bad_stamps;
    Skip(m, "header.stamp " + std::to_string(*stamp) + " ns");
  } else if (last != std::numeric_limits<int64_t>::min() && *stamp < last) {
    ++s.out_of_order;
    Skip(m, "header.stamp " + std::to_string(last - *stamp) + " ns before the previous one");
  } else if (*stamp == last) {
    ++s.duplicates;
    Skip(m, "header.stamp equal to the previous one (duplicate)");
  } else {
    last = *stamp;
    return true;
  }
  return false;
}

bool BagMessageStream::Accept(const BagMessage& m, StreamMessage* out) {
  TopicStreamStats& s = stats_[m.topic];
  const BagTopic& topic = reader_->topics()[m.topic];
  std::string error;
  if (!DecodeMessage(kinds_[m.topic], topic.encoding, m.data, &decoded_, &error)) {
    ++s.decode_errors;
    Skip(m, "does not decode as " + topic.type + ": " + error);
    return false;
  }
  if (!CheckStamp(m, s)) return false;
  const bool cloud = decoded_.kind == RosMessageKind::kPointCloud2;
  if (cloud && !CloudFromPointCloud2(decoded_.cloud, options_.cloud, &cloud_, &error)) {
    ++s.decode_errors;
    Skip(m, "inconsistent PointCloud2: " + error);
    return false;
  }
  if (cloud) s.non_finite_points += cloud_.non_finite_points;
  const bool empty =
      cloud ? cloud_.scan.points.empty()
            : RoleOf(decoded_.kind) == TopicRole::kLidar && decoded_.packets.packets.empty();
  if (empty) {
    ++s.empty;
    Skip(m, cloud ? "a cloud without a finite point" : "no packets");
    return false;
  }
  ++s.delivered;
  *out = {roles_[m.topic],          decoded_.kind, m.topic, m.index, m.log_time_ns, &decoded_,
          cloud ? &cloud_ : nullptr};
  return true;
}

bool BagMessageStream::Next(StreamMessage* out) {
  BagMessage m;
  while (reader_->Next(&m)) {
    if (roles_[m.topic] == TopicRole::kNone) continue;
    if (Accept(m, out)) return true;
  }
  return false;
}

}  // namespace swlio::drivers::bag
