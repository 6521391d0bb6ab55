// MCAP writer (mcap_writer.h). Record layouts: foxglove/mcap 95d0673 website/docs/spec/index.md;
// which CRC covers what: research/bags.md §3.3.

#include "swlio/drivers/bag/mcap_writer.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "swlio/drivers/bag/compress.h"
#include "swlio/drivers/bag/crc32.h"

namespace swlio::drivers::bag {
namespace {

constexpr size_t kFlushBytes = size_t{4} << 20;

const char* CompressionName(Compression c) {
  switch (c) {
    case Compression::kZstd:
      return "zstd";
    case Compression::kLz4Frame:
      return "lz4";
    default:
      return "";
  }
}

}  // namespace

McapWriter::McapWriter(const McapWriterOptions& options, std::FILE* file)
    : options_(options), file_(file) {
  if (options_.compression == Compression::kBz2) options_.compression = Compression::kZstd;
  out_.insert(out_.end(), mcap::kMagic.begin(), mcap::kMagic.end());
  data_crc_ = Crc32(mcap::kMagic);
  mcap::RecordBuilder header;
  header.String(options_.profile).String(options_.library);
  Emit(mcap::kHeader, header.content());
}

McapWriter::~McapWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

std::unique_ptr<McapWriter> McapWriter::Create(const std::string& path,
                                               const McapWriterOptions& options,
                                               std::string* error) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    *error = path + ": cannot create: " + std::strerror(errno);
    return nullptr;
  }
  return std::unique_ptr<McapWriter>(new McapWriter(options, f));
}

std::unique_ptr<McapWriter> McapWriter::CreateInMemory(const McapWriterOptions& options) {
  return std::unique_ptr<McapWriter>(new McapWriter(options, nullptr));
}

void McapWriter::Emit(uint8_t opcode, std::span<const uint8_t> content) {
  const size_t start = out_.size();
  mcap::AppendRecord(opcode, content, &out_);
  const std::span<const uint8_t> record(out_.data() + start, out_.size() - start);
  if (in_data_section_) data_crc_ = Crc32Update(data_crc_, record);
  if (in_summary_) summary_crc_ = Crc32Update(summary_crc_, record);
}

uint16_t McapWriter::AddSchema(const std::string& name,
                               const std::string& encoding,
                               const std::string& data) {
  const uint16_t id = ++schemas_;
  mcap::RecordBuilder b;
  b.U16(id).String(name).String(encoding).String(data);  // Bytes with a u32 length
  schema_records_.push_back(b.content());
  Emit(mcap::kSchema, b.content());
  return id;
}

uint16_t McapWriter::AddChannel(uint16_t schema_id,
                                const std::string& topic,
                                const std::string& message_encoding,
                                const std::map<std::string, std::string>& metadata) {
  const uint16_t id = ++channels_;
  mcap::RecordBuilder b;
  b.U16(id).U16(schema_id).String(topic).String(message_encoding).StringMap(metadata);
  channel_records_.push_back(b.content());
  channel_counts_[id] = 0;
  Emit(mcap::kChannel, b.content());
  return id;
}

bool McapWriter::Write(uint16_t channel_id,
                       int64_t log_time_ns,
                       int64_t publish_time_ns,
                       std::span<const uint8_t> data,
                       uint32_t sequence) {
  if (closed_ || channel_id == 0 || channel_id > channels_ || log_time_ns < 0 ||
      publish_time_ns < 0) {
    return false;
  }
  const auto t = static_cast<uint64_t>(log_time_ns);
  mcap::RecordBuilder b;
  b.U16(channel_id).U32(sequence).U64(t).U64(static_cast<uint64_t>(publish_time_ns)).Raw(data);
  start_time_ = message_count_ == 0 ? t : std::min(start_time_, t);
  end_time_ = std::max(end_time_, t);
  ++message_count_;
  ++channel_counts_[channel_id];
  if (options_.chunk_bytes == 0) {
    Emit(mcap::kMessage, b.content());
    return Flush(false);
  }
  if (chunk_.empty()) chunk_start_ = chunk_end_ = t;
  chunk_start_ = std::min(chunk_start_, t);
  chunk_end_ = std::max(chunk_end_, t);
  chunk_index_[channel_id].emplace_back(t, chunk_.size());
  mcap::AppendRecord(mcap::kMessage, b.content(), &chunk_);
  if (chunk_.size() >= options_.chunk_bytes) return CloseChunk();
  return !io_failed_;
}

bool McapWriter::CloseChunk() {
  if (chunk_.empty()) return true;
  std::vector<uint8_t> compressed;
  if (!Compress(options_.compression, chunk_, &compressed, options_.zstd_level)) return false;
  const uint64_t chunk_offset = Offset();
  mcap::RecordBuilder b;
  b.U64(chunk_start_).U64(chunk_end_).U64(chunk_.size());
  b.U32(options_.chunk_crc ? Crc32(chunk_) : 0).String(CompressionName(options_.compression));
  b.U64(compressed.size()).Raw(compressed);
  Emit(mcap::kChunk, b.content());
  const uint64_t chunk_length = Offset() - chunk_offset;
  const uint64_t index_offset = Offset();
  const std::map<uint16_t, uint64_t> index_offsets = WriteMessageIndexes();
  mcap::RecordBuilder offsets;
  for (const auto& [channel, offset] : index_offsets) offsets.U16(channel).U64(offset);
  mcap::RecordBuilder ci;
  ci.U64(chunk_start_).U64(chunk_end_).U64(chunk_offset).U64(chunk_length);
  ci.U32(static_cast<uint32_t>(offsets.content().size())).Raw(offsets.content());
  ci.U64(Offset() - index_offset).String(CompressionName(options_.compression));
  ci.U64(compressed.size()).U64(chunk_.size());
  chunk_index_records_.push_back(ci.content());
  ++chunk_count_;
  chunk_.clear();
  chunk_index_.clear();
  return Flush(false);
}

std::map<uint16_t, uint64_t> McapWriter::WriteMessageIndexes() {
  std::map<uint16_t, uint64_t> offsets;
  if (!options_.message_index) return offsets;
  for (const auto& [channel, entries] : chunk_index_) {
    offsets[channel] = Offset();
    mcap::RecordBuilder b;
    b.U16(channel).U32(static_cast<uint32_t>(entries.size() * 16));
    for (const auto& [time, offset] : entries) b.U64(time).U64(offset);
    Emit(mcap::kMessageIndex, b.content());
  }
  return offsets;
}

std::vector<uint8_t> McapWriter::StatisticsContent() const {
  mcap::RecordBuilder counts;
  for (const auto& [channel, n] : channel_counts_) counts.U16(channel).U64(n);
  mcap::RecordBuilder b;
  b.U64(message_count_).U16(schemas_).U32(channels_).U32(0).U32(0).U32(chunk_count_);
  b.U64(start_time_).U64(end_time_);
  b.U32(static_cast<uint32_t>(counts.content().size())).Raw(counts.content());
  return b.content();
}

void McapWriter::SummaryGroup(uint8_t opcode, const std::vector<std::vector<uint8_t>>& records) {
  if (records.empty()) return;
  const uint64_t start = Offset();
  for (const auto& r : records) Emit(opcode, r);
  mcap::RecordBuilder b;
  b.U8(opcode).U64(start).U64(Offset() - start);
  offset_records_.push_back(b.content());
}

void McapWriter::WriteSummary() {
  const uint64_t summary_start = Offset();
  in_summary_ = true;
  SummaryGroup(mcap::kSchema, schema_records_);
  SummaryGroup(mcap::kChannel, channel_records_);
  SummaryGroup(mcap::kStatistics, {StatisticsContent()});
  SummaryGroup(mcap::kChunkIndex, chunk_index_records_);
  const uint64_t offsets_start = Offset();
  for (const auto& r : offset_records_) Emit(mcap::kSummaryOffset, r);
  WriteFooter(summary_start, offsets_start);
}

void McapWriter::WriteFooter(uint64_t summary_start, uint64_t summary_offset_start) {
  // The summary CRC covers the footer's opcode, length and both offsets, not its CRC field.
  mcap::RecordBuilder head;
  head.U8(mcap::kFooter)
      .U64(mcap::kFooterContentBytes)
      .U64(summary_start)
      .U64(summary_offset_start);
  uint32_t crc = 0;
  if (summary_start != 0 && options_.summary_crc) {
    crc = Crc32Update(summary_crc_, head.content());
  }
  in_summary_ = false;
  mcap::RecordBuilder footer;
  footer.U64(summary_start).U64(summary_offset_start).U32(crc);
  Emit(mcap::kFooter, footer.content());
}

bool McapWriter::Flush(bool all) {
  if (file_ == nullptr || io_failed_) return !io_failed_;
  if (!all && out_.size() < kFlushBytes) return true;
  if (std::fwrite(out_.data(), 1, out_.size(), file_) != out_.size()) io_failed_ = true;
  flushed_bytes_ += out_.size();
  out_.clear();
  return !io_failed_;
}

bool McapWriter::Close(std::string* error) {
  if (closed_) return true;
  closed_ = true;
  if (!CloseChunk()) {
    *error = "compression failed";
    return false;
  }
  mcap::RecordBuilder data_end;
  data_end.U32(options_.data_section_crc ? data_crc_ : 0);
  in_data_section_ = false;
  Emit(mcap::kDataEnd, data_end.content());
  if (options_.summary) {
    WriteSummary();
  } else {
    WriteFooter(0, 0);
  }
  out_.insert(out_.end(), mcap::kMagic.begin(), mcap::kMagic.end());
  if (!Flush(true) || (file_ != nullptr && std::fflush(file_) != 0)) {
    *error = std::string("write failed: ") + std::strerror(errno);
    return false;
  }
  return true;
}

}  // namespace swlio::drivers::bag
