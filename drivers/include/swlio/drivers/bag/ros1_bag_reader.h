#pragma once
/// @file
/// Reads ROS 1 bags, format version 2.0 (records: ros1_bag_records.h), in one linear pass, so
/// bags that were never closed (no index section) read like closed ones. Chunks are "none",
/// "bz2" (libbz2) or "lz4" (roslz4 = LZ4 frame format, utilities/roslz4/src/lz4s.c, read with
/// liblz4's frame API). A chunk that fails to decompress or states a wrong size is skipped with
/// a warning naming its offset; records of unknown ops are skipped and counted; a file cut
/// short is read up to its last complete record. Connections of one topic and type (several
/// publishers) become one topic. Messages come in receive-time order (IndexedMessages).
/// Message bytes are ROS 1 serialization (MessageEncoding::kRos1).

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
#include "swlio/drivers/bag/ros1_bag_records.h"
#include "swlio/drivers/bag/warning_log.h"

namespace swlio::drivers::bag {

class Ros1BagReader final : public BagReader {
 public:
  /// Opens and indexes `path`. Returns nullptr and sets `error` (naming the file) when it is
  /// not a ROS bag, or a version other than 2.0.
  static std::unique_ptr<Ros1BagReader> Open(const std::string& path,
                                             const BagReadLimits& limits,
                                             std::string* error);
  /// The same on an in-memory image (copied); `name` stands for the path in messages.
  static std::unique_ptr<Ros1BagReader> OpenBytes(std::span<const uint8_t> bytes,
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

 private:
  Ros1BagReader(std::string path, const BagReadLimits& limits)
      : path_(std::move(path)), limits_(limits) {}
  bool Index(std::string* error);
  /// One top-level record at `offset`.
  void TopRecord(const ros1::RecordHeader& h, const ros1::Record& r, size_t offset);
  void ReadChunk(const ros1::RecordHeader& h, std::span<const uint8_t> data, size_t offset);
  void ReadChunkRecords(std::span<const uint8_t> records, uint32_t chunk, size_t offset);
  void AddConnection(const ros1::RecordHeader& h, std::span<const uint8_t> data, size_t offset);
  void AddMessage(const ros1::RecordHeader& h,
                  std::span<const uint8_t> data,
                  uint32_t chunk,
                  uint64_t data_offset,
                  size_t at);
  /// Warns when the bag header promises more than the file holds.
  void CheckCompleteness();
  void BuildTopics();
  std::string At(size_t offset) const;

  struct Connection {
    std::string topic, type, md5sum, definition;
    bool operator==(const Connection&) const = default;
  };

  std::string path_;
  BagReadLimits limits_;
  std::unique_ptr<MappedFile> mapped_;
  std::vector<uint8_t> owned_;
  std::span<const uint8_t> file_;
  std::map<uint32_t, Connection> connections_;
  IndexedMessages index_;
  std::vector<BagTopic> topics_;
  std::vector<uint8_t> scratch_;
  std::map<std::string, uint64_t> chunk_compressions_;
  bool have_bag_header_ = false;
  uint64_t index_pos_ = 0;  ///< from the bag header; 0: the bag was never closed
  uint32_t chunk_count_ = 0;
  uint32_t chunks_seen_ = 0;
  std::string error_;
  WarningLog warnings_{kMaxWarnings};
  BagReadStats stats_;
};

}  // namespace swlio::drivers::bag
