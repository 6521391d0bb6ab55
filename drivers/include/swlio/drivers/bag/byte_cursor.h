#pragma once
/// @file
/// Bounded little-endian reads over a byte span, for container records (MCAP, ROS 1 bags).
/// A read past the end fails, leaves the cursor where it was and returns false; nothing is
/// ever read outside the span. Values are read with the explicit-endian helpers of bytes.h.

#include <cstdint>
#include <span>
#include <string_view>

#include "swlio/drivers/bytes.h"

namespace swlio::drivers::bag {

class ByteCursor {
 public:
  explicit ByteCursor(std::span<const uint8_t> bytes) : bytes_(bytes) {}

  size_t position() const { return pos_; }
  size_t remaining() const { return bytes_.size() - pos_; }
  bool empty() const { return pos_ == bytes_.size(); }

  bool U8(uint8_t* v) {
    if (remaining() < 1) return false;
    *v = bytes_[pos_++];
    return true;
  }
  bool U16(uint16_t* v) { return Fixed(2, v, bytes::ReadU16Le); }
  bool U32(uint32_t* v) { return Fixed(4, v, bytes::ReadU32Le); }
  bool U64(uint64_t* v) { return Fixed(8, v, bytes::ReadU64Le); }
  /// `n` raw bytes as a view into the span.
  bool Bytes(uint64_t n, std::span<const uint8_t>* out) {
    if (n > remaining()) return false;
    *out = bytes_.subspan(pos_, static_cast<size_t>(n));
    pos_ += static_cast<size_t>(n);
    return true;
  }
  /// A u32 byte length, then that many bytes (MCAP String, ROS 1 header values).
  bool String32(std::string_view* out) {
    const size_t start = pos_;
    uint32_t n = 0;
    std::span<const uint8_t> b;
    if (!U32(&n) || !Bytes(n, &b)) {
      pos_ = start;
      return false;
    }
    *out = std::string_view(reinterpret_cast<const char*>(b.data()), b.size());
    return true;
  }
  /// A length prefix of 4 (`U32`) or 8 (`U64`) bytes, then that many bytes.
  bool Bytes32(std::span<const uint8_t>* out) { return Prefixed<uint32_t>(out); }
  bool Bytes64(std::span<const uint8_t>* out) { return Prefixed<uint64_t>(out); }
  bool Skip(uint64_t n) {
    if (n > remaining()) return false;
    pos_ += static_cast<size_t>(n);
    return true;
  }

 private:
  template <typename T, typename F>
  bool Fixed(size_t n, T* v, F read) {
    if (remaining() < n) return false;
    *v = read(bytes_.data() + pos_);
    pos_ += n;
    return true;
  }
  template <typename L>
  bool Prefixed(std::span<const uint8_t>* out) {
    const size_t start = pos_;
    L n = 0;
    bool ok = false;
    if constexpr (sizeof(L) == 4) {
      ok = U32(&n);
    } else {
      ok = U64(&n);
    }
    if (!ok || !Bytes(n, out)) {
      pos_ = start;
      return false;
    }
    return true;
  }

  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
};

}  // namespace swlio::drivers::bag
