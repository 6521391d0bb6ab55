#pragma once
/// @file
/// Writes MCAP files (records in mcap_records.h) the way readers and Foxglove expect them
/// (research/bags.md §3.5, §3.7): Header, Schema and Channel records as they are added,
/// messages in chunks (none, zstd or LZ4-frame compression, each followed by one MessageIndex
/// per channel), DataEnd with the data-section CRC, then the summary (every Schema and Channel,
/// Statistics, one ChunkIndex per chunk), the SummaryOffset records, the Footer with the summary
/// CRC, and the closing magic. Options turn chunking, CRCs and the summary off, which the
/// reader's tests need and `fastwrite`-style files have.
///
/// Output goes to a file (buffered, written as chunks close) or to memory.

#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "swlio/drivers/bag/decompress.h"
#include "swlio/drivers/bag/mcap_records.h"

namespace swlio::drivers::bag {

struct McapWriterOptions {
  std::string profile = "ros2";
  std::string library = "swlio";
  Compression compression = Compression::kZstd;  ///< kNone, kZstd or kLz4Frame
  int zstd_level = 1;
  /// A chunk closes once its uncompressed records reach this size. 0: no chunks, messages are
  /// top-level records (and no MessageIndex or ChunkIndex is written).
  uint64_t chunk_bytes = uint64_t{1} << 20;
  bool chunk_crc = true;         ///< else uncompressed_crc = 0
  bool data_section_crc = true;  ///< else DataEnd's CRC = 0
  bool message_index = true;     ///< MessageIndex records after each chunk
  bool summary = true;           ///< summary and summary offset sections
  bool summary_crc = true;       ///< else the Footer's CRC = 0
};

class McapWriter {
 public:
  /// Creates (truncates) `path`. Returns nullptr and sets `error` on failure.
  static std::unique_ptr<McapWriter> Create(const std::string& path,
                                            const McapWriterOptions& options,
                                            std::string* error);
  /// Writes into memory; the file is `bytes()` after Close().
  static std::unique_ptr<McapWriter> CreateInMemory(const McapWriterOptions& options);
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// Adds a schema (ids from 1); e.g. name "sensor_msgs/msg/Imu", encoding "ros2msg".
  uint16_t AddSchema(const std::string& name, const std::string& encoding, const std::string& data);
  /// Adds a channel (ids from 1); `schema_id` 0 for none; e.g. message_encoding "cdr".
  uint16_t AddChannel(uint16_t schema_id,
                      const std::string& topic,
                      const std::string& message_encoding,
                      const std::map<std::string, std::string>& metadata = {});
  /// Appends one message. Times are ns since the epoch (≥ 0). False on an unknown channel,
  /// a negative time or an I/O error.
  bool Write(uint16_t channel_id,
             int64_t log_time_ns,
             int64_t publish_time_ns,
             std::span<const uint8_t> data,
             uint32_t sequence = 0);
  /// Finishes the file. False (with `error`) on an I/O or compression error.
  bool Close(std::string* error);

  const std::vector<uint8_t>& bytes() const { return out_; }

 private:
  explicit McapWriter(const McapWriterOptions& options, std::FILE* file);
  uint64_t Offset() const { return flushed_bytes_ + out_.size(); }
  /// Appends a record, feeding the running CRCs.
  void Emit(uint8_t opcode, std::span<const uint8_t> content);
  bool CloseChunk();
  /// One MessageIndex per channel of the closed chunk; returns their offsets by channel.
  std::map<uint16_t, uint64_t> WriteMessageIndexes();
  void WriteSummary();
  /// Emits `records` as one group of the summary and records its SummaryOffset.
  void SummaryGroup(uint8_t opcode, const std::vector<std::vector<uint8_t>>& records);
  std::vector<uint8_t> StatisticsContent() const;
  void WriteFooter(uint64_t summary_start, uint64_t summary_offset_start);
  bool Flush(bool all);

  McapWriterOptions options_;
  std::FILE* file_ = nullptr;
  std::vector<uint8_t> out_;    ///< not yet flushed (file) or everything (memory)
  uint64_t flushed_bytes_ = 0;  ///< bytes already in the file
  uint32_t data_crc_ = 0;       ///< running CRC of everything written before DataEnd
  uint32_t summary_crc_ = 0;    ///< running CRC from the summary start
  bool in_data_section_ = true;
  bool in_summary_ = false;
  uint32_t chunk_count_ = 0;
  std::vector<std::vector<uint8_t>> schema_records_;
  std::vector<std::vector<uint8_t>> channel_records_;
  std::map<uint16_t, uint64_t> channel_counts_;
  uint16_t schemas_ = 0;
  uint16_t channels_ = 0;
  // The open chunk.
  std::vector<uint8_t> chunk_;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_index_;  ///< time, offset
  uint64_t chunk_start_ = 0;
  uint64_t chunk_end_ = 0;
  // Summary material.
  std::vector<std::vector<uint8_t>> chunk_index_records_;
  std::vector<std::vector<uint8_t>> offset_records_;
  uint64_t message_count_ = 0;
  uint64_t start_time_ = 0;
  uint64_t end_time_ = 0;
  bool io_failed_ = false;
  bool closed_ = false;
};

}  // namespace swlio::drivers::bag
