#include "swlio/daemon/blackbox/ring_segments.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace swlio::daemon {
namespace {

constexpr char kPrefix[] = "seg-";

/// The number of a segment folder name, or -1.
int64_t SegmentNumber(const std::filesystem::path& p) {
  const std::string name = p.filename().string();
  if (name.rfind(kPrefix, 0) != 0 || name.size() <= sizeof kPrefix - 1) return -1;
  int64_t n = 0;
  for (size_t i = sizeof kPrefix - 1; i < name.size(); ++i) {
    if (name[i] < '0' || name[i] > '9' || n > 1'000'000'000'000) return -1;
    n = n * 10 + (name[i] - '0');
  }
  return n;
}

}  // namespace

uint64_t DirectoryBytes(const std::filesystem::path& dir) {
  std::error_code ec;
  uint64_t total = 0;
  for (auto it = std::filesystem::recursive_directory_iterator(dir, ec);
       !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    std::error_code size_ec;
    if (it->is_regular_file(size_ec)) {
      const uintmax_t n = it->file_size(size_ec);
      if (!size_ec) total += n;
    }
  }
  return total;
}

std::vector<std::filesystem::path> RingSegments::Leftovers() const {
  std::vector<std::pair<int64_t, std::filesystem::path>> found;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator(dir_, ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
    const int64_t n = SegmentNumber(it->path());
    if (n >= 0 && it->is_directory(ec)) found.emplace_back(n, it->path());
  }
  std::sort(found.begin(), found.end());
  std::vector<std::filesystem::path> out;
  out.reserve(found.size());
  for (auto& [n, p] : found) out.push_back(std::move(p));
  return out;
}

std::filesystem::path RingSegments::NextDir() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!scanned_) {
    scanned_ = true;
    for (const std::filesystem::path& p : Leftovers())
      next_index_ = std::max<uint64_t>(next_index_, static_cast<uint64_t>(SegmentNumber(p)) + 1);
  }
  char name[32];
  std::snprintf(name, sizeof name, "%s%06llu", kPrefix,
                static_cast<unsigned long long>(next_index_++));
  return dir_ / name;
}

void RingSegments::Add(SegmentInfo segment) {
  std::lock_guard<std::mutex> lock(mutex_);
  bytes_ += segment.bytes;
  segments_.push_back(std::move(segment));
}

void RingSegments::DeleteOldest() {
  std::error_code ec;
  std::filesystem::remove_all(segments_.front().dir, ec);  // a failure leaves a stray folder
  bytes_ -= std::min(bytes_, segments_.front().bytes);
  segments_.erase(segments_.begin());
  ++deleted_;
}

size_t RingSegments::Trim(int64_t now_ns,
                          const RingBounds& bounds,
                          uint64_t open_bytes,
                          int64_t keep_from_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  size_t n = 0;
  while (!segments_.empty()) {
    const bool too_big = bytes_ + open_bytes > bounds.max_bytes;
    const bool too_old = now_ns - segments_.front().start_ns > bounds.max_span_ns &&
                         segments_.front().end_ns < keep_from_ns;
    if (!too_big && !too_old) break;
    DeleteOldest();
    ++n;
  }
  return n;
}

std::vector<SegmentInfo> RingSegments::Overlapping(int64_t from_ns, int64_t to_ns) const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<SegmentInfo> out;
  for (const SegmentInfo& s : segments_) {
    if (s.end_ns >= from_ns && s.start_ns <= to_ns) out.push_back(s);
  }
  return out;
}

size_t RingSegments::count() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return segments_.size();
}

uint64_t RingSegments::bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return bytes_;
}

int64_t RingSegments::oldest_start_ns() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return segments_.empty() ? 0 : segments_.front().start_ns;
}

uint64_t RingSegments::deleted() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return deleted_;
}

}  // namespace swlio::daemon
