#pragma once
/// @file
/// The writing side of message_reader.h: one ROS message serialized as XCDR1 little-endian
/// (encapsulation header 00 01 00 00, alignment relative to byte 4, strings with their NUL) or
/// in the ROS 1 format (no alignment, no NUL, Header with seq). For MCAP export and for tests.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"

namespace swlio::drivers::bag {

class MessageWriter {
 public:
  /// Starts a message (kCdr writes the encapsulation header); `encoding` kUnknown acts as kCdr.
  explicit MessageWriter(MessageEncoding encoding);

  void U8(uint8_t v) { bytes_.push_back(v); }
  void U16(uint16_t v);
  void U32(uint32_t v);
  void F32(float v);
  void F64(double v);
  void String(std::string_view s);
  void Bytes(std::span<const uint8_t> b) { bytes_.insert(bytes_.end(), b.begin(), b.end()); }
  /// builtin_interfaces/Time from ns since the epoch (floor division: negative times keep
  /// 0 ≤ nanosec < 10⁹).
  void Time(int64_t t_ns);
  /// std_msgs/Header (ROS 1: seq 0 first).
  void Header(int64_t stamp_ns, std::string_view frame_id);
  /// Pads with zeros to a multiple of 4 after the encapsulation header, as the RMWs do (CDR only).
  void PadToFour();

  const std::vector<uint8_t>& bytes() const { return bytes_; }
  std::vector<uint8_t> Take() { return std::move(bytes_); }

 private:
  void Align(size_t n);
  void Raw(uint64_t v, size_t n);

  std::vector<uint8_t> bytes_;
  bool ros1_ = false;
};

}  // namespace swlio::drivers::bag
