#pragma once
/// @file
/// A whole file mapped read-only into memory (mmap), so the MCAP and ROS 1 readers parse one
/// byte span, the same code that the fuzzers drive from memory. Pages are read on demand.
/// @note A file truncated by another process while mapped raises SIGBUS on access; bags are
///       read after recording, and a recorder that appends only never shrinks the file.

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace swlio::drivers::bag {

class MappedFile {
 public:
  /// Maps `path`. Returns nullptr and sets `error` (naming the file) when it cannot be opened,
  /// is not a regular file or cannot be mapped.
  static std::unique_ptr<MappedFile> Open(const std::string& path, std::string* error);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::span<const uint8_t> bytes() const { return {data_, size_}; }

 private:
  MappedFile(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  const uint8_t* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace swlio::drivers::bag
