// The numbers and the text of `swlio-bag info` (bag_summary.h).

#include "bag_summary.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <limits>
#include <optional>

#include "swlio/drivers/bag/message_decoder.h"
#include "swlio/drivers/bag/topic_selection.h"

namespace swlio::tools {
namespace {

namespace bag = drivers::bag;

std::string Seconds(int64_t t_ns) {
  char b[40];
  const int64_t s = t_ns / 1'000'000'000;
  const int64_t ns = t_ns % 1'000'000'000;
  std::snprintf(b, sizeof(b), "%" PRId64 ".%09" PRId64, s, ns < 0 ? -ns : ns);
  return b;
}

std::string Fixed(double v, int digits) {
  char b[40];
  std::snprintf(b, sizeof(b), "%.*f", digits, v);
  return b;
}

struct Decoder {
  bag::DecodedMessage decoded;
  std::vector<int64_t> last_stamp;
};

void Inspect(const bag::BagMessage& m, const bag::BagTopic& topic, Decoder& d, TopicSummary& t) {
  if (t.kind == bag::RosMessageKind::kUnknown || topic.encoding == bag::MessageEncoding::kUnknown) {
    return;
  }
  std::string error;
  if (!bag::DecodeMessage(t.kind, topic.encoding, m.data, &d.decoded, &error)) {
    if (t.decode_errors++ == 0) t.first_error = "#" + std::to_string(m.index) + ": " + error;
    return;
  }
  if (bag::RoleOf(d.decoded.kind) == bag::TopicRole::kLidar &&
      d.decoded.kind != bag::RosMessageKind::kPointCloud2) {
    t.packets += d.decoded.packets.packets.size();
  }
  const std::optional<int64_t> stamp = bag::HeaderStamp(d.decoded);
  if (!stamp) return;
  int64_t& last = d.last_stamp[m.topic];
  if (last != std::numeric_limits<int64_t>::min() && *stamp < last) ++t.out_of_order;
  if (*stamp == last) ++t.duplicates;
  last = *stamp;  // each stamp against the message just before it
}

std::string Pad(std::string s, size_t width) {
  if (s.size() < width) s.resize(width, ' ');
  return s;
}

std::string TopicLine(const TopicSummary& t, size_t name_width, size_t type_width) {
  const bag::BagTopic& b = t.topic;
  std::string line = "  " + Pad(b.name, name_width) + "  " + Pad(b.type, type_width) + "  " +
                     std::to_string(b.message_count) + " msgs";
  if (b.message_count > 1 && b.last_log_time_ns > b.first_log_time_ns) {
    const double hz = static_cast<double>(b.message_count - 1) * 1e9 /
                      static_cast<double>(b.last_log_time_ns - b.first_log_time_ns);
    line += "  " + Fixed(hz, hz < 10.0 ? 2 : 1) + " Hz";
  }
  if (b.message_count > 0) {
    line += "  " + Seconds(b.first_log_time_ns) + " … " + Seconds(b.last_log_time_ns);
  }
  line += "  [" + std::string(bag::RoleName(bag::RoleOf(t.kind))) + ": " + bag::KindName(t.kind);
  if (t.packets > 0) line += ", " + std::to_string(t.packets) + " packets";
  return line + "]\n";
}

std::string TopicWarnings(const TopicSummary& t) {
  std::string w;
  const std::string n = "  " + t.topic.name + ": ";
  if (t.kind == bag::RosMessageKind::kUnknown)
    w += n + "type " + t.topic.type + " is not read by swlio\n";
  if (t.decode_errors > 0) {
    w += n + std::to_string(t.decode_errors) + " messages do not decode as " + t.topic.type +
         " (first " + t.first_error + ")\n";
  }
  if (t.out_of_order > 0) {
    w += n + std::to_string(t.out_of_order) + " header stamps earlier than the one before\n";
  }
  if (t.duplicates > 0) w += n + std::to_string(t.duplicates) + " repeated header stamps\n";
  return w;
}

}  // namespace

BagSummary Summarize(bag::BagReader& reader, bool decode) {
  BagSummary s;
  s.path = reader.path();
  s.storage = reader.StorageDescription();
  for (const bag::BagTopic& t : reader.topics()) {
    TopicSummary ts;
    ts.topic = t;
    ts.kind = bag::ClassifyTopic(t);
    s.topics.push_back(std::move(ts));
  }
  Decoder d;
  d.last_stamp.assign(reader.topics().size(), std::numeric_limits<int64_t>::min());
  bag::BagMessage m;
  while (reader.Next(&m)) {
    TopicSummary& t = s.topics[m.topic];
    if (s.messages++ == 0) s.start_ns = m.log_time_ns;
    s.end_ns = m.log_time_ns;
    s.bytes += m.data.size();
    t.bytes += m.data.size();
    if (decode) Inspect(m, reader.topics()[m.topic], d, t);
  }
  s.read_error = reader.error();
  s.reader_warnings = reader.warnings();
  s.reader_warnings_dropped = reader.warnings_dropped();
  return s;
}

std::string FormatSummary(const BagSummary& s) {
  std::string out = "file:      " + s.path + "\nstorage:   " + s.storage + "\n";
  out += "duration:  " + Fixed(static_cast<double>(s.end_ns - s.start_ns) * 1e-9, 3) + " s";
  if (s.messages > 0) out += "  (" + Seconds(s.start_ns) + " … " + Seconds(s.end_ns) + ")";
  out += "\nmessages:  " + std::to_string(s.messages) + " (" +
         Fixed(static_cast<double>(s.bytes) / 1e6, 1) + " MB)\ntopics:\n";
  std::string warnings;
  size_t name_width = 0;
  size_t type_width = 0;
  for (const TopicSummary& t : s.topics) {
    name_width = std::max(name_width, t.topic.name.size());
    type_width = std::max(type_width, t.topic.type.size());
  }
  for (const TopicSummary& t : s.topics) {
    out += TopicLine(t, name_width, type_width);
    warnings += TopicWarnings(t);
  }
  for (const std::string& w : s.reader_warnings) warnings += "  " + w + "\n";
  if (s.reader_warnings_dropped > 0) {
    warnings += "  … and " + std::to_string(s.reader_warnings_dropped) + " more\n";
  }
  if (!s.read_error.empty()) warnings += "  reading stopped: " + s.read_error + "\n";
  if (!warnings.empty()) out += "warnings:\n" + warnings;
  return out;
}

}  // namespace swlio::tools
