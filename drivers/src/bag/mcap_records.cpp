// MCAP record parsers and builder (mcap_records.h). Field orders from foxglove/mcap 95d0673
// website/docs/spec/index.md, one section per record ("Header (op=0x01)", …).

#include "swlio/drivers/bag/mcap_records.h"

#include "swlio/drivers/bag/byte_cursor.h"

namespace swlio::drivers::bag::mcap {
namespace {

bool ReadString(ByteCursor& c, std::string* out) {
  std::string_view v;
  if (!c.String32(&v)) return false;
  out->assign(v);
  return true;
}

/// Map<String, String>: u32 byte length, then key/value Strings filling exactly that length.
bool ReadStringMap(ByteCursor& c, std::map<std::string, std::string>* out) {
  std::span<const uint8_t> bytes;
  if (!c.Bytes32(&bytes)) return false;
  ByteCursor m(bytes);
  while (!m.empty()) {
    std::string key;
    std::string value;
    if (!ReadString(m, &key) || !ReadString(m, &value)) return false;
    (*out)[key] = value;
  }
  return true;
}

}  // namespace

bool ParseHeader(std::span<const uint8_t> content, Header* out) {
  ByteCursor c(content);
  return ReadString(c, &out->profile) && ReadString(c, &out->library);
}

bool ParseFooter(std::span<const uint8_t> content, Footer* out) {
  ByteCursor c(content);
  return c.U64(&out->summary_start) && c.U64(&out->summary_offset_start) &&
         c.U32(&out->summary_crc);
}

bool ParseSchema(std::span<const uint8_t> content, Schema* out) {
  ByteCursor c(content);
  std::span<const uint8_t> data;
  if (!c.U16(&out->id) || !ReadString(c, &out->name) || !ReadString(c, &out->encoding) ||
      !c.Bytes32(&data)) {
    return false;
  }
  out->data.assign(data.begin(), data.end());
  return true;
}

bool ParseChannel(std::span<const uint8_t> content, Channel* out) {
  ByteCursor c(content);
  return c.U16(&out->id) && c.U16(&out->schema_id) && ReadString(c, &out->topic) &&
         ReadString(c, &out->message_encoding) && ReadStringMap(c, &out->metadata);
}

bool ParseMessage(std::span<const uint8_t> content, Message* out) {
  ByteCursor c(content);
  if (!c.U16(&out->channel_id) || !c.U32(&out->sequence) || !c.U64(&out->log_time) ||
      !c.U64(&out->publish_time)) {
    return false;
  }
  out->data = content.subspan(kMessageHeaderBytes);
  return true;
}

bool ParseChunk(std::span<const uint8_t> content, Chunk* out) {
  ByteCursor c(content);
  return c.U64(&out->message_start_time) && c.U64(&out->message_end_time) &&
         c.U64(&out->uncompressed_size) && c.U32(&out->uncompressed_crc) &&
         ReadString(c, &out->compression) && c.Bytes64(&out->records);
}

bool ParseStatistics(std::span<const uint8_t> content, Statistics* out) {
  ByteCursor c(content);
  uint16_t schemas = 0;
  uint32_t channels = 0;
  uint32_t attachments = 0;
  uint32_t metadata = 0;
  uint32_t chunks = 0;
  uint64_t start = 0;
  uint64_t end = 0;
  std::span<const uint8_t> counts;
  if (!c.U64(&out->message_count) || !c.U16(&schemas) || !c.U32(&channels) ||
      !c.U32(&attachments) || !c.U32(&metadata) || !c.U32(&chunks) || !c.U64(&start) ||
      !c.U64(&end) || !c.Bytes32(&counts)) {
    return false;
  }
  ByteCursor m(counts);
  while (!m.empty()) {
    uint16_t channel = 0;
    uint64_t n = 0;
    if (!m.U16(&channel) || !m.U64(&n)) return false;
    out->channel_message_counts[channel] = n;
  }
  return true;
}

bool ParseDataEnd(std::span<const uint8_t> content, uint32_t* data_section_crc) {
  ByteCursor c(content);
  return c.U32(data_section_crc);
}

RecordBuilder& RecordBuilder::U8(uint8_t v) {
  content_.push_back(v);
  return *this;
}

RecordBuilder& RecordBuilder::U16(uint16_t v) {
  for (int i = 0; i < 2; ++i) content_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  return *this;
}

RecordBuilder& RecordBuilder::U32(uint32_t v) {
  for (int i = 0; i < 4; ++i) content_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  return *this;
}

RecordBuilder& RecordBuilder::U64(uint64_t v) {
  for (int i = 0; i < 8; ++i) content_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  return *this;
}

RecordBuilder& RecordBuilder::String(std::string_view s) {
  U32(static_cast<uint32_t>(s.size()));
  content_.insert(content_.end(), s.begin(), s.end());
  return *this;
}

RecordBuilder& RecordBuilder::Raw(std::span<const uint8_t> b) {
  content_.insert(content_.end(), b.begin(), b.end());
  return *this;
}

RecordBuilder& RecordBuilder::StringMap(const std::map<std::string, std::string>& m) {
  RecordBuilder entries;
  for (const auto& [k, v] : m) entries.String(k).String(v);
  U32(static_cast<uint32_t>(entries.content().size()));
  return Raw(entries.content());
}

void AppendRecord(uint8_t opcode, std::span<const uint8_t> content, std::vector<uint8_t>* out) {
  out->push_back(opcode);
  const uint64_t n = content.size();
  for (int i = 0; i < 8; ++i) out->push_back(static_cast<uint8_t>(n >> (8 * i)));
  out->insert(out->end(), content.begin(), content.end());
}

}  // namespace swlio::drivers::bag::mcap
