#pragma once
/// @file
/// A bounded list of warning lines (the first BagReader::kMaxWarnings kept, the rest counted),
/// shared by the bag readers so that a file with a million bad records cannot fill memory.

#include <cstdint>
#include <string>
#include <vector>

namespace swlio::drivers::bag {

class WarningLog {
 public:
  explicit WarningLog(size_t max_lines = 100) : max_lines_(max_lines) {}

  void Add(std::string line) {
    if (lines_.size() < max_lines_) {
      lines_.push_back(std::move(line));
    } else {
      ++dropped_;
    }
  }
  const std::vector<std::string>& lines() const { return lines_; }
  uint64_t dropped() const { return dropped_; }

 private:
  size_t max_lines_;
  std::vector<std::string> lines_;
  uint64_t dropped_ = 0;
};

}  // namespace swlio::drivers::bag
