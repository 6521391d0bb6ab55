#pragma once
/// @file
/// A bounded reader of one serialized ROS message, in either wire format:
///
/// - ROS 2, XCDR1 ("plain CDR", what the ROS 2 RMWs write; research/bags.md §2.1). Bytes 0–1:
///   encapsulation id, big-endian: 0x0000 CDR_BE, 0x0001 CDR_LE; bytes 2–3 options (ignored).
///   XCDR2 ids 0x0006–0x000b are refused (DDS-XTypes 1.3 §7.6.2.1.2; foxglove/cdr
///   src/EncapsulationKind.ts). Alignment origin is byte 4: a primitive of n bytes starts at
///   a multiple of n from it (8-byte types at 8). string = u32 length including the NUL, bytes,
///   NUL; T[] = u32 count then elements; T[N] = elements only; nested types add no padding of
///   their own. Up to 3 trailing padding bytes are allowed after the last field.
/// - ROS 1 (roscpp_serialization serialization.h; wiki.ros.org/msg): little-endian, no
///   alignment; string = u32 length then bytes, no NUL; time = u32 sec + u32 nsec; the Header
///   starts with `uint32 seq`. No trailing bytes.
///
/// Why not Fast CDR (libfastcdr-dev 1.0.26): it reports malformed input by throwing
/// (NotEnoughMemoryException), copies every byte sequence into a std::vector (94 KB per
/// RoboSense scan message, where a view suffices), and cannot read the ROS 1 format, which
/// needs a reader of its own anyway. The fixed message types read here need only the rules above.
///
/// Failure is sticky: the first read that does not fit records where and what it was, every
/// later read returns zero, and `ok()` turns false. Decoders read all fields, then check once.
/// No read ever leaves the span; a sequence count is checked against the bytes left before the
/// caller reserves memory for it.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "swlio/drivers/bag/bag_reader.h"

namespace swlio::drivers::bag {

inline constexpr int64_t kNsPerS = 1'000'000'000;

/// std_msgs/Header (ROS 2: stamp, frame_id; ROS 1: seq, stamp, frame_id).
struct RosHeader {
  int64_t stamp_ns = 0;       ///< header.stamp, ns since the Unix epoch (as the publisher set it)
  std::string_view frame_id;  ///< view into the message bytes
};

class MessageReader {
 public:
  /// Starts reading `bytes` as `encoding` (kCdr checks the encapsulation header). False with
  /// `error` set for an unknown encoding or encapsulation.
  bool Begin(std::span<const uint8_t> bytes, MessageEncoding encoding, std::string* error);

  bool ok() const { return failed_at_ == nullptr; }
  bool ros1() const { return ros1_; }
  size_t position() const { return pos_; }
  size_t remaining() const { return bytes_.size() - pos_; }
  /// Where reading failed: "byte 1290: packets[3].data needs 1248 bytes, 37 left".
  std::string Failure() const;
  /// True when reading succeeded and no more than the allowed padding is left.
  bool Finish();

  uint8_t U8(const char* what);
  int8_t I8(const char* what) { return static_cast<int8_t>(U8(what)); }
  uint16_t U16(const char* what);
  uint32_t U32(const char* what);
  int32_t I32(const char* what) { return static_cast<int32_t>(U32(what)); }
  float F32(const char* what);
  double F64(const char* what);
  std::string_view String(const char* what);
  /// A sequence's element count, failing when `count × min_element_bytes` exceeds what is left.
  uint32_t SequenceLength(const char* what, size_t min_element_bytes);
  /// `n` raw bytes (uint8[N] or the body of uint8[]), no alignment.
  std::span<const uint8_t> Bytes(size_t n, const char* what);
  /// builtin_interfaces/Time (ROS 2: int32 sec, uint32 nanosec; ROS 1: u32 sec, u32 nsec) in ns;
  /// fails when the nanoseconds are ≥ 10⁹.
  int64_t Time(const char* what);
  RosHeader Header();
  /// Marks a field whose value the type does not allow (decoders' own checks).
  void Invalid(const char* what) { Fail(what, 0, Problem::kValue); }
  /// `n` float64 values into `out`.
  void F64Array(double* out, size_t n, const char* what);

 private:
  enum class Problem : uint8_t { kShort, kValue, kTrailing };
  bool Need(size_t n, const char* what);
  void Align(size_t n);
  void Fail(const char* what, size_t need, Problem problem = Problem::kShort);

  std::span<const uint8_t> bytes_;
  size_t pos_ = 0;
  size_t origin_ = 0;
  bool ros1_ = false;
  bool big_endian_ = false;
  const char* failed_at_ = nullptr;
  Problem problem_ = Problem::kShort;
  size_t failed_pos_ = 0;
  size_t failed_need_ = 0;
};

}  // namespace swlio::drivers::bag
