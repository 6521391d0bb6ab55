#pragma once
/// @file
/// Reads MCAP files (records: mcap_records.h), written from the specification (foxglove/mcap
/// 95d0673 website/docs/spec/index.md); no MCAP library is packaged in Debian.
///
/// One linear pass over the data section, which every valid file has, so the summary and the
/// indexes are never needed: files without them (or cut before them) read the same. The pass
///   - takes Schema and Channel records wherever they are (top level, in chunks, in the
///     summary; duplicates of one id must agree, else the first wins with a warning);
///   - decompresses each Chunk ("" none, "zstd", "lz4" = LZ4 frame) and checks its
///     uncompressed CRC when not 0; a chunk with an unknown compression, a wrong size or CRC,
///     or a damaged stream is skipped whole, with a warning naming its file offset;
///   - skips records of unknown opcodes (spec: readers must) and counts them;
///   - checks DataEnd's data-section CRC and the Footer's summary CRC when not 0 (a mismatch
///     is a warning: the messages' own chunks were checked), and compares the summary's
///     Statistics with what it found.
/// A file that ends early (no DataEnd, no Footer, a record cut short) is read up to its last
/// complete record, with a warning naming the offset. Channels of one topic, schema name and
/// encoding (several publishers) become one topic. Messages come in log_time order
/// (IndexedMessages).

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/bag/indexed_messages.h"
#include "swlio/drivers/bag/mapped_file.h"
#include "swlio/drivers/bag/mcap_records.h"
#include "swlio/drivers/bag/warning_log.h"

namespace swlio::drivers::bag {

class McapReader final : public BagReader {
 public:
  /// Opens and indexes `path`. Returns nullptr and sets `error` (naming the file) when it is
  /// not an MCAP file (magic, Header record).
  static std::unique_ptr<McapReader> Open(const std::string& path,
                                          const BagReadLimits& limits,
                                          std::string* error);
  /// The same on an in-memory image (copied); `name` stands for the path in messages.
  static std::unique_ptr<McapReader> OpenBytes(std::span<const uint8_t> bytes,
                                               const std::string& name,
                                               const BagReadLimits& limits,
                                               std::string* error);

  std::string StorageDescription() const override;
  const std::vector<BagTopic>& topics() const override { return topics_; }
  bool Next(BagMessage* message) override;
  const std::string& error() const override { return error_; }
  const std::vector<std::string>& warnings() const override { return warnings_.lines(); }
  uint64_t warnings_dropped() const override { return warnings_.dropped(); }
  const BagReadStats& stats() const override { return stats_; }
  const std::string& path() const override { return path_; }

  const mcap::Header& header() const { return header_; }
  bool has_summary() const { return footer_.summary_start != 0; }

 private:
  McapReader(std::string path, const BagReadLimits& limits)
      : path_(std::move(path)), limits_(limits) {}
  bool Index(std::string* error);
  /// Walks the data section; returns the offset after its last complete record.
  size_t ReadDataSection(size_t pos);
  /// Handles one top-level record at `offset`; false once the data section ends.
  bool DataRecord(uint8_t opcode, std::span<const uint8_t> content, size_t offset);
  void ReadChunk(std::span<const uint8_t> content, size_t offset);
  void ReadChunkRecords(std::span<const uint8_t> records, uint32_t chunk, size_t offset);
  void CheckDataEnd(std::span<const uint8_t> content, size_t offset);
  void ReadFooterAndSummary(size_t data_end);
  void ReadSummary(size_t start, size_t end);
  void AddSchema(std::span<const uint8_t> content, size_t offset);
  void AddChannel(std::span<const uint8_t> content, size_t offset);
  void AddMessage(std::span<const uint8_t> content, uint32_t chunk, uint64_t offset, size_t at);
  void BuildTopics();
  std::string At(size_t offset) const;

  std::string path_;
  BagReadLimits limits_;
  std::unique_ptr<MappedFile> mapped_;
  std::vector<uint8_t> owned_;
  std::span<const uint8_t> file_;
  mcap::Header header_;
  mcap::Footer footer_;
  std::map<uint16_t, mcap::Schema> schemas_;
  std::map<uint16_t, mcap::Channel> channels_;
  bool have_statistics_ = false;
  mcap::Statistics statistics_;
  IndexedMessages index_;
  std::vector<BagTopic> topics_;
  std::vector<uint8_t> scratch_;
  std::string error_;
  WarningLog warnings_{kMaxWarnings};
  BagReadStats stats_;
};

}  // namespace swlio::drivers::bag
