#pragma once
/// @file
/// The black box's ring: closed segments (recording folders ring/seg-NNNNNN/, oldest first)
/// and the rule that bounds them. Shared by the recorder thread (adds, trims) and the incident
/// keeper (reads the segments an incident spans): every method locks.

#include <cstdint>
#include <filesystem>
#include <mutex>
#include <vector>

namespace swlio::daemon {

struct SegmentInfo {
  std::filesystem::path dir;
  int64_t start_ns = 0;  ///< daemon time of its first and last moments
  int64_t end_ns = 0;
  uint64_t bytes = 0;  ///< on disk
};

struct RingBounds {
  int64_t max_span_ns = 0;  ///< sensor time from the oldest segment's start to now
  uint64_t max_bytes = 0;   ///< closed segments plus the open one
};

class RingSegments {
 public:
  explicit RingSegments(std::filesystem::path ring_dir) : dir_(std::move(ring_dir)) {}

  /// Segment folders left in the ring directory by an earlier run, oldest first.
  std::vector<std::filesystem::path> Leftovers() const;
  /// The folder of the next segment (numbers continue after any leftover).
  std::filesystem::path NextDir();

  void Add(SegmentInfo segment);
  /// Deletes the oldest segments while the ring exceeds `bounds`: by span only those that end
  /// before `keep_from_ns` (an incident still needs the others); by bytes any, oldest first.
  /// `open_bytes`: the open segment's. Returns how many were deleted.
  size_t Trim(int64_t now_ns, const RingBounds& bounds, uint64_t open_bytes, int64_t keep_from_ns);
  /// The segments overlapping [from_ns, to_ns], oldest first.
  std::vector<SegmentInfo> Overlapping(int64_t from_ns, int64_t to_ns) const;

  size_t count() const;
  uint64_t bytes() const;
  int64_t oldest_start_ns() const;  ///< 0 when empty
  uint64_t deleted() const;

 private:
  void DeleteOldest();  ///< with the mutex held

  std::filesystem::path dir_;
  mutable std::mutex mutex_;
  std::vector<SegmentInfo> segments_;
  uint64_t bytes_ = 0;
  uint64_t next_index_ = 0;
  bool scanned_ = false;
  uint64_t deleted_ = 0;
};

/// The bytes of every regular file under `dir` (0 when it does not exist).
uint64_t DirectoryBytes(const std::filesystem::path& dir);

}  // namespace swlio::daemon
