// ROS 1 bag v2.0 record framing (ros1_bag_records.h).

#include "swlio/drivers/bag/ros1_bag_records.h"

#include <algorithm>

#include "swlio/drivers/bag/byte_cursor.h"
#include "swlio/drivers/bag/message_reader.h"
#include "swlio/drivers/bytes.h"

namespace swlio::drivers::bag::ros1 {

bool RecordHeader::Parse(std::span<const uint8_t> bytes) {
  fields_.clear();
  ByteCursor c(bytes);
  while (!c.empty()) {
    std::span<const uint8_t> field;
    if (!c.Bytes32(&field)) return false;
    const auto eq = std::find(field.begin(), field.end(), uint8_t{'='});
    if (eq == field.end()) return false;
    const auto name_len = static_cast<size_t>(eq - field.begin());
    fields_.emplace_back(std::string_view(reinterpret_cast<const char*>(field.data()), name_len),
                         field.subspan(name_len + 1));
  }
  return true;
}

bool RecordHeader::Find(std::string_view name, std::span<const uint8_t>* value) const {
  for (const auto& [n, v] : fields_) {
    if (n != name) continue;
    *value = v;
    return true;
  }
  return false;
}

bool RecordHeader::U8(std::string_view name, uint8_t* v) const {
  std::span<const uint8_t> b;
  if (!Find(name, &b) || b.size() != 1) return false;
  *v = b[0];
  return true;
}

bool RecordHeader::U32(std::string_view name, uint32_t* v) const {
  std::span<const uint8_t> b;
  if (!Find(name, &b) || b.size() != 4) return false;
  *v = bytes::ReadU32Le(b.data());
  return true;
}

bool RecordHeader::U64(std::string_view name, uint64_t* v) const {
  std::span<const uint8_t> b;
  if (!Find(name, &b) || b.size() != 8) return false;
  *v = bytes::ReadU64Le(b.data());
  return true;
}

bool RecordHeader::Time(std::string_view name, int64_t* t_ns) const {
  std::span<const uint8_t> b;
  if (!Find(name, &b) || b.size() != 8) return false;
  const uint32_t sec = bytes::ReadU32Le(b.data());
  const uint32_t nsec = bytes::ReadU32Le(b.data() + 4);
  if (nsec >= kNsPerS) return false;
  *t_ns = static_cast<int64_t>(sec) * kNsPerS + nsec;
  return true;
}

bool RecordHeader::Text(std::string_view name, std::string* v) const {
  std::span<const uint8_t> b;
  if (!Find(name, &b)) return false;
  v->assign(b.begin(), b.end());
  return true;
}

bool ReadRecord(std::span<const uint8_t> bytes, Record* out) {
  ByteCursor c(bytes);
  if (!c.Bytes32(&out->header) || !c.Bytes32(&out->data)) return false;
  out->size = c.position();
  return true;
}

void AppendRecord(const std::vector<std::pair<std::string, std::vector<uint8_t>>>& fields,
                  std::span<const uint8_t> data,
                  std::vector<uint8_t>* out) {
  std::vector<uint8_t> header;
  const auto u32 = [](std::vector<uint8_t>* b, size_t v) {
    for (int i = 0; i < 4; ++i) b->push_back(static_cast<uint8_t>(v >> (8 * i)));
  };
  for (const auto& [name, value] : fields) {
    u32(&header, name.size() + 1 + value.size());
    header.insert(header.end(), name.begin(), name.end());
    header.push_back('=');
    header.insert(header.end(), value.begin(), value.end());
  }
  u32(out, header.size());
  out->insert(out->end(), header.begin(), header.end());
  u32(out, data.size());
  out->insert(out->end(), data.begin(), data.end());
}

}  // namespace swlio::drivers::bag::ros1
