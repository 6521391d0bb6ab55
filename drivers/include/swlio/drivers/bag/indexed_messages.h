#pragma once
/// @file
/// The message index the chunked containers (MCAP, ROS 1 bags) build in one linear pass over a
/// file, and the time-ordered iteration over it.
///
/// Reading order: these formats store messages in chunks, and neither promises that chunks or
/// the messages inside them are in time order, so the first pass records every message's
/// receive time and place (in the file, or at an offset inside a chunk's uncompressed records)
/// and a stable sort orders them by time (ties keep file order). Iteration then decompresses
/// each chunk when a message in it is next; a few decompressed chunks are kept, so recordings
/// whose chunks overlap a little in time are not decompressed over and over. The index costs
/// 32 bytes per message (10 minutes of RS16 scans at 10 Hz and IMU at 400 Hz: ≈ 8 MB).

#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/bag/decompress.h"
#include "swlio/drivers/bag/warning_log.h"

namespace swlio::drivers::bag {

/// A chunk's compressed bytes in the file.
struct ChunkLocation {
  uint64_t file_offset = 0;  ///< first compressed byte
  uint64_t size = 0;         ///< compressed bytes
  uint64_t uncompressed_size = 0;
  Compression compression = Compression::kNone;
};

class IndexedMessages {
 public:
  static constexpr uint32_t kInFile = 0xFFFFFFFFu;  ///< `chunk` of a message outside chunks

  /// Registers a chunk; returns its number for Add().
  uint32_t AddChunk(const ChunkLocation& chunk);
  /// Records a message of container channel `channel` at `offset` (in the file when `chunk` is
  /// kInFile, else in that chunk's uncompressed bytes).
  void Add(int64_t log_time_ns, uint32_t channel, uint32_t chunk, uint64_t offset, uint64_t size);

  /// Maps channels to topics (dropping, counting and reporting messages of unknown channels),
  /// fills each topic's count and span, and sorts by time. Call once, after the pass.
  void Finish(const std::unordered_map<uint32_t, uint32_t>& topic_of_channel,
              std::vector<BagTopic>* topics,
              const std::string& path,
              WarningLog* warnings,
              BagReadStats* stats);

  /// The next message in time order, its bytes from `file`. A chunk that no longer
  /// decompresses (it did in the first pass) ends reading with `error`.
  bool Next(std::span<const uint8_t> file, BagMessage* message, std::string* error);

  size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    int64_t log_time_ns;
    uint64_t offset;
    uint32_t size;
    uint32_t chunk;
    uint32_t channel;  ///< container channel before Finish(), topic index after
  };
  struct CachedChunk {
    uint32_t chunk = kInFile;
    std::vector<uint8_t> bytes;
    uint64_t last_use = 0;
  };
  /// The uncompressed records of `chunk` (a view into the file when uncompressed).
  bool ChunkBytes(std::span<const uint8_t> file,
                  uint32_t chunk,
                  std::span<const uint8_t>* out,
                  std::string* error);

  std::vector<Entry> entries_;
  std::vector<ChunkLocation> chunks_;
  std::vector<uint64_t> next_index_;  ///< per topic
  size_t next_ = 0;
  std::vector<CachedChunk> cache_;
  uint64_t uses_ = 0;
};

}  // namespace swlio::drivers::bag
