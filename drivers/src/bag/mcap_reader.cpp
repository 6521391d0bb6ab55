// MCAP reader: one linear pass over the data section (mcap_reader.h). Record layouts and
// placement rules: foxglove/mcap 95d0673 website/docs/spec/index.md.

#include "swlio/drivers/bag/mcap_reader.h"

#include <algorithm>
#include <limits>

#include "swlio/drivers/bag/byte_cursor.h"
#include "swlio/drivers/bag/crc32.h"
#include "swlio/drivers/bytes.h"

namespace swlio::drivers::bag {
namespace {

constexpr uint64_t kMaxLogTime = static_cast<uint64_t>(std::numeric_limits<int64_t>::max());
constexpr size_t kFooterRecordBytes = mcap::kRecordPrefixBytes + mcap::kFooterContentBytes;

bool StartsWithMagic(std::span<const uint8_t> b) {
  return b.size() >= mcap::kMagic.size() &&
         std::equal(mcap::kMagic.begin(), mcap::kMagic.end(), b.begin());
}

std::string Hex(uint32_t v) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string s = "0x";
  for (int shift = 28; shift >= 0; shift -= 4) s += kDigits[(v >> shift) & 0xF];
  return s;
}

}  // namespace

std::unique_ptr<McapReader> McapReader::Open(const std::string& path,
                                             const BagReadLimits& limits,
                                             std::string* error) {
  auto mapped = MappedFile::Open(path, error);
  if (!mapped) return nullptr;
  std::unique_ptr<McapReader> reader(new McapReader(path, limits));
  reader->file_ = mapped->bytes();
  reader->mapped_ = std::move(mapped);
  if (!reader->Index(error)) return nullptr;
  return reader;
}

std::unique_ptr<McapReader> McapReader::OpenBytes(std::span<const uint8_t> bytes,
                                                  const std::string& name,
                                                  const BagReadLimits& limits,
                                                  std::string* error) {
  std::unique_ptr<McapReader> reader(new McapReader(name, limits));
  reader->owned_.assign(bytes.begin(), bytes.end());
  reader->file_ = reader->owned_;
  if (!reader->Index(error)) return nullptr;
  return reader;
}

std::string McapReader::At(size_t offset) const {
  return path_ + ": byte " + std::to_string(offset) + ": ";
}

bool McapReader::Index(std::string* error) {
  if (!StartsWithMagic(file_)) {
    *error = path_ + ": not an MCAP file (no \\x89MCAP0\\r\\n magic)";
    return false;
  }
  const size_t pos = mcap::kMagic.size();
  ByteCursor c(file_.subspan(pos));
  uint8_t op = 0;
  uint64_t len = 0;
  std::span<const uint8_t> content;
  if (!c.U8(&op) || !c.U64(&len) || op != mcap::kHeader || !c.Bytes(len, &content) ||
      !mcap::ParseHeader(content, &header_)) {
    *error = path_ + ": MCAP magic without a complete Header record (truncated or damaged)";
    return false;
  }
  ReadDataSection(pos);
  BuildTopics();
  if (have_statistics_ && statistics_.message_count != index_.size()) {
    warnings_.Add(path_ + ": the summary's Statistics count " +
                  std::to_string(statistics_.message_count) + " messages; " +
                  std::to_string(index_.size()) + " were found");
  }
  return true;
}

size_t McapReader::ReadDataSection(size_t pos) {
  for (;;) {
    ByteCursor c(file_.subspan(pos));
    uint8_t op = 0;
    uint64_t len = 0;
    std::span<const uint8_t> content;
    if (!c.U8(&op) || !c.U64(&len)) {
      warnings_.Add(At(pos) +
                    "the file ends inside the data section (no DataEnd record); "
                    "read up to here (truncated?)");
      return pos;
    }
    if (!c.Bytes(len, &content)) {
      warnings_.Add(At(pos) + "record " + Hex(op) + " of " + std::to_string(len) +
                    " bytes runs past the end of the file; read up to here (truncated?)");
      return pos;
    }
    const size_t next = pos + mcap::kRecordPrefixBytes + content.size();
    if (!DataRecord(op, content, pos)) {
      if (op == mcap::kDataEnd) ReadFooterAndSummary(next);
      return next;
    }
    pos = next;
  }
}

bool McapReader::DataRecord(uint8_t opcode, std::span<const uint8_t> content, size_t offset) {
  switch (opcode) {
    case mcap::kHeader:
      if (offset != mcap::kMagic.size()) warnings_.Add(At(offset) + "a second Header; ignored");
      return true;
    case mcap::kSchema:
      AddSchema(content, offset);
      return true;
    case mcap::kChannel:
      AddChannel(content, offset);
      return true;
    case mcap::kMessage:
      AddMessage(content, IndexedMessages::kInFile,
                 static_cast<uint64_t>(content.data() - file_.data()), offset);
      return true;
    case mcap::kChunk:
      ReadChunk(content, offset);
      return true;
    case mcap::kDataEnd:
      CheckDataEnd(content, offset);
      return false;
    case mcap::kFooter:
      warnings_.Add(At(offset) + "Footer without a DataEnd record before it");
      return false;
    case mcap::kMessageIndex:
    case mcap::kAttachment:
    case mcap::kMetadata:
      return true;  // allowed here, not needed
    default:
      ++stats_.records_skipped;  // unknown, private, or summary-only opcodes
      return true;
  }
}

void McapReader::ReadChunk(std::span<const uint8_t> content, size_t offset) {
  mcap::Chunk chunk;
  Compression compression = Compression::kNone;
  std::string why;
  if (!mcap::ParseChunk(content, &chunk)) {
    why = "its fields do not fit the record";
  } else if (!ParseCompression(chunk.compression, &compression) ||
             compression == Compression::kBz2) {
    why = "unknown compression '" + chunk.compression + "'";
  } else if (chunk.uncompressed_size > limits_.max_chunk_bytes) {
    why = std::to_string(chunk.uncompressed_size) + " uncompressed bytes, over the limit";
  }
  std::span<const uint8_t> records = chunk.records;
  if (why.empty() && compression != Compression::kNone) {
    if (Decompress(compression, chunk.records, chunk.uncompressed_size, &scratch_, &why)) {
      records = scratch_;
    }
  } else if (why.empty() && chunk.records.size() != chunk.uncompressed_size) {
    why = "uncompressed records of " + std::to_string(chunk.records.size()) +
          " bytes, the chunk states " + std::to_string(chunk.uncompressed_size);
  }
  if (why.empty() && chunk.uncompressed_crc != 0) {
    ++stats_.crc_checked;
    const uint32_t crc = Crc32(records);
    if (crc != chunk.uncompressed_crc) {
      why = "CRC " + Hex(crc) + ", the chunk states " + Hex(chunk.uncompressed_crc);
    }
  }
  if (!why.empty()) {
    warnings_.Add(At(offset) + "chunk skipped: " + why);
    ++stats_.chunks_skipped;
    return;
  }
  const uint32_t n = index_.AddChunk({static_cast<uint64_t>(chunk.records.data() - file_.data()),
                                      chunk.records.size(), chunk.uncompressed_size, compression});
  ReadChunkRecords(records, n, offset);
}

void McapReader::ReadChunkRecords(std::span<const uint8_t> records, uint32_t chunk, size_t offset) {
  ByteCursor c(records);
  while (!c.empty()) {
    const size_t at = c.position();
    uint8_t op = 0;
    uint64_t len = 0;
    std::span<const uint8_t> content;
    if (!c.U8(&op) || !c.U64(&len) || !c.Bytes(len, &content)) {
      warnings_.Add(At(offset) + "chunk record at +" + std::to_string(at) +
                    " runs past the chunk's end; the rest of the chunk skipped");
      return;
    }
    if (op == mcap::kSchema) {
      AddSchema(content, offset);
    } else if (op == mcap::kChannel) {
      AddChannel(content, offset);
    } else if (op == mcap::kMessage) {
      AddMessage(content, chunk, at + mcap::kRecordPrefixBytes, offset);
    } else {
      ++stats_.records_skipped;  // not allowed in a chunk, or unknown
    }
  }
}

void McapReader::AddMessage(std::span<const uint8_t> content,
                            uint32_t chunk,
                            uint64_t offset,
                            size_t at) {
  mcap::Message m;
  std::string why;
  if (!mcap::ParseMessage(content, &m)) {
    why = "shorter than a Message's 22-byte header";
  } else if (m.log_time > kMaxLogTime) {
    why = "log_time beyond 2262";
  } else if (m.data.size() > limits_.max_message_bytes) {
    why = std::to_string(m.data.size()) + " bytes, over the limit";
  }
  if (!why.empty()) {
    warnings_.Add(At(at) + "message skipped: " + why);
    ++stats_.messages_skipped;
    return;
  }
  index_.Add(static_cast<int64_t>(m.log_time), m.channel_id, chunk,
             offset + mcap::kMessageHeaderBytes, m.data.size());
}

void McapReader::CheckDataEnd(std::span<const uint8_t> content, size_t offset) {
  uint32_t stored = 0;
  if (!mcap::ParseDataEnd(content, &stored) || stored == 0) return;
  ++stats_.crc_checked;
  const uint32_t crc = Crc32(file_.first(offset));
  if (crc != stored) {
    warnings_.Add(At(offset) + "data section CRC " + Hex(crc) + ", DataEnd states " + Hex(stored) +
                  " (the chunks' own CRCs were checked)");
  }
}

void McapReader::ReadFooterAndSummary(size_t data_end) {
  const size_t n = file_.size();
  if (n < data_end + kFooterRecordBytes + mcap::kMagic.size() ||
      !std::equal(mcap::kMagic.begin(), mcap::kMagic.end(), file_.end() - 8)) {
    warnings_.Add(At(data_end) + "no Footer and closing magic after the data section (truncated?)");
    return;
  }
  const size_t footer_at = n - mcap::kMagic.size() - kFooterRecordBytes;
  const uint8_t* f = file_.data() + footer_at;
  if (f[0] != mcap::kFooter || bytes::ReadU64Le(f + 1) != mcap::kFooterContentBytes ||
      !mcap::ParseFooter(file_.subspan(footer_at + mcap::kRecordPrefixBytes, 20), &footer_)) {
    warnings_.Add(At(footer_at) + "no Footer record before the closing magic");
    return;
  }
  if (footer_.summary_start == 0) return;
  const uint64_t end = footer_.summary_offset_start != 0 ? footer_.summary_offset_start : footer_at;
  if (footer_.summary_start < data_end || end < footer_.summary_start || end > footer_at) {
    warnings_.Add(At(footer_at) + "Footer's summary offsets point outside the file; ignored");
    footer_.summary_start = 0;
    return;
  }
  if (footer_.summary_crc != 0) {
    ++stats_.crc_checked;
    // From the summary's start through the Footer's two offsets (not its CRC field).
    const size_t covered = footer_at + mcap::kRecordPrefixBytes + 16 - footer_.summary_start;
    const uint32_t crc = Crc32(file_.subspan(footer_.summary_start, covered));
    if (crc != footer_.summary_crc) {
      warnings_.Add(At(footer_at) + "summary CRC " + Hex(crc) + ", Footer states " +
                    Hex(footer_.summary_crc) + "; the summary is not used");
      return;
    }
  }
  ReadSummary(footer_.summary_start, end);
}

void McapReader::ReadSummary(size_t start, size_t end) {
  ByteCursor c(file_.subspan(start, end - start));
  while (!c.empty()) {
    const size_t at = start + c.position();
    uint8_t op = 0;
    uint64_t len = 0;
    std::span<const uint8_t> content;
    if (!c.U8(&op) || !c.U64(&len) || !c.Bytes(len, &content)) {
      warnings_.Add(At(at) + "summary record runs past the summary's end; rest ignored");
      return;
    }
    if (op == mcap::kSchema) AddSchema(content, at);
    if (op == mcap::kChannel) AddChannel(content, at);
    if (op == mcap::kStatistics) have_statistics_ = mcap::ParseStatistics(content, &statistics_);
  }
}

void McapReader::AddSchema(std::span<const uint8_t> content, size_t offset) {
  mcap::Schema s;
  if (!mcap::ParseSchema(content, &s) || s.id == 0) {
    warnings_.Add(At(offset) + "unreadable Schema record (or id 0); ignored");
    return;
  }
  const auto [it, added] = schemas_.emplace(s.id, s);
  if (!added && !(it->second == s)) {
    warnings_.Add(At(offset) + "Schema " + std::to_string(s.id) +
                  " differs from its first definition; the first is kept");
  }
}

void McapReader::AddChannel(std::span<const uint8_t> content, size_t offset) {
  mcap::Channel ch;
  if (!mcap::ParseChannel(content, &ch)) {
    warnings_.Add(At(offset) + "unreadable Channel record; ignored");
    return;
  }
  const auto [it, added] = channels_.emplace(ch.id, ch);
  if (!added && !(it->second == ch)) {
    warnings_.Add(At(offset) + "Channel " + std::to_string(ch.id) +
                  " differs from its first definition; the first is kept");
  }
}

void McapReader::BuildTopics() {
  std::unordered_map<uint32_t, uint32_t> topic_of_channel;
  for (const auto& [id, ch] : channels_) {
    BagTopic t;
    t.name = ch.topic;
    t.encoding_name = ch.message_encoding;
    t.encoding = EncodingFromName(ch.message_encoding);
    if (const auto s = schemas_.find(ch.schema_id); s != schemas_.end()) {
      t.type = s->second.name;
      t.definition = s->second.data;
      t.definition_encoding = s->second.encoding;
    } else if (ch.schema_id != 0) {
      warnings_.Add(path_ + ": channel " + std::to_string(id) + " (" + ch.topic +
                    ") names schema " + std::to_string(ch.schema_id) + ", which is not defined");
    }
    if (const auto md5 = ch.metadata.find("md5sum"); md5 != ch.metadata.end()) {
      t.md5sum = md5->second;
    }
    // Channels of one topic, type and encoding (several publishers) are one topic.
    const auto same = [&t](const BagTopic& o) {
      return o.name == t.name && o.type == t.type && o.encoding_name == t.encoding_name;
    };
    auto it = std::find_if(topics_.begin(), topics_.end(), same);
    if (it == topics_.end()) it = topics_.insert(topics_.end(), std::move(t));
    topic_of_channel[id] = static_cast<uint32_t>(it - topics_.begin());
  }
  index_.Finish(topic_of_channel, &topics_, path_, &warnings_, &stats_);
}

std::string McapReader::StorageDescription() const {
  return "mcap (profile '" + header_.profile + "', library '" + header_.library + "', " +
         (has_summary() ? "with" : "without") + " summary)";
}

bool McapReader::Next(BagMessage* message) {
  if (!error_.empty()) return false;
  std::string error;
  if (!index_.Next(file_, message, &error)) {
    if (!error.empty()) error_ = path_ + ": " + error;
    return false;
  }
  ++stats_.messages_returned;
  stats_.bytes_returned += message->data.size();
  return true;
}

}  // namespace swlio::drivers::bag
