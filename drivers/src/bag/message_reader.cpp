// Bounded XCDR1 / ROS 1 message reader; the wire rules are in message_reader.h.

#include "swlio/drivers/bag/message_reader.h"

#include <bit>
#include <cstdio>

#include "swlio/drivers/bytes.h"

namespace swlio::drivers::bag {
namespace {

constexpr size_t kCdrHeaderBytes = 4;
constexpr size_t kCdrMaxTrailingPad = 3;
constexpr uint16_t kCdrBe = 0x0000;
constexpr uint16_t kCdrLe = 0x0001;

}  // namespace

bool MessageReader::Begin(std::span<const uint8_t> bytes,
                          MessageEncoding encoding,
                          std::string* error) {
  *this = MessageReader();
  bytes_ = bytes;
  if (encoding == MessageEncoding::kRos1) {
    ros1_ = true;
    return true;
  }
  if (encoding != MessageEncoding::kCdr) {
    *error = "unknown message encoding";
    return false;
  }
  if (bytes.size() < kCdrHeaderBytes) {
    *error = "shorter than the 4-byte CDR encapsulation header";
    return false;
  }
  const uint16_t id = bytes::ReadU16Be(bytes.data());
  if (id != kCdrBe && id != kCdrLe) {
    char hex[8];
    std::snprintf(hex, sizeof(hex), "%04x", id);
    *error =
        std::string("encapsulation 0x") + hex + " is not XCDR1 (CDR_BE 0x0000 / CDR_LE 0x0001)";
    return false;
  }
  big_endian_ = id == kCdrBe;
  pos_ = origin_ = kCdrHeaderBytes;
  return true;
}

std::string MessageReader::Failure() const {
  if (ok()) return {};
  std::string at = "byte " + std::to_string(failed_pos_) + ": " + failed_at_;
  switch (problem_) {
    case Problem::kShort:
      return at + " needs " + std::to_string(failed_need_) + " bytes, " +
             std::to_string(bytes_.size() - failed_pos_) + " left";
    case Problem::kValue:
      return at + " has an impossible value";
    case Problem::kTrailing:
      return at + ": " + std::to_string(bytes_.size() - failed_pos_) +
             " bytes left over (not this type's layout)";
  }
  return at;
}

bool MessageReader::Finish() {
  if (!ok()) return false;
  const size_t allowed = ros1_ ? 0 : kCdrMaxTrailingPad;
  if (remaining() > allowed) {
    Fail("end of message", 0, Problem::kTrailing);
    return false;
  }
  return true;
}

void MessageReader::Fail(const char* what, size_t need, Problem problem) {
  if (!ok()) return;
  problem_ = problem;
  failed_at_ = what;
  failed_pos_ = pos_;
  failed_need_ = need;
}

void MessageReader::Align(size_t n) {
  if (ros1_ || !ok()) return;
  const size_t pad = (n - (pos_ - origin_) % n) % n;
  if (pad > remaining()) {
    pos_ = bytes_.size();  // the next Need() fails
    return;
  }
  pos_ += pad;
}

bool MessageReader::Need(size_t n, const char* what) {
  if (!ok()) return false;
  if (n > remaining()) {
    Fail(what, n);
    return false;
  }
  return true;
}

uint8_t MessageReader::U8(const char* what) {
  if (!Need(1, what)) return 0;
  return bytes_[pos_++];
}

uint16_t MessageReader::U16(const char* what) {
  Align(2);
  if (!Need(2, what)) return 0;
  const uint8_t* p = bytes_.data() + pos_;
  pos_ += 2;
  return big_endian_ ? bytes::ReadU16Be(p) : bytes::ReadU16Le(p);
}

uint32_t MessageReader::U32(const char* what) {
  Align(4);
  if (!Need(4, what)) return 0;
  const uint8_t* p = bytes_.data() + pos_;
  pos_ += 4;
  return big_endian_ ? bytes::ReadU32Be(p) : bytes::ReadU32Le(p);
}

float MessageReader::F32(const char* what) { return std::bit_cast<float>(U32(what)); }

double MessageReader::F64(const char* what) {
  Align(8);
  if (!Need(8, what)) return 0.0;
  const uint8_t* p = bytes_.data() + pos_;
  pos_ += 8;
  return big_endian_ ? bytes::ReadF64Be(p) : bytes::ReadF64Le(p);
}

void MessageReader::F64Array(double* out, size_t n, const char* what) {
  for (size_t i = 0; i < n; ++i) out[i] = F64(what);
}

std::string_view MessageReader::String(const char* what) {
  const uint32_t n = U32(what);
  if (!ok()) return {};
  if (!ros1_ && n == 0) {  // a CDR string holds at least its NUL
    Fail(what, 1, Problem::kValue);
    return {};
  }
  if (!Need(n, what)) return {};
  const auto* p = reinterpret_cast<const char*>(bytes_.data() + pos_);
  pos_ += n;
  if (ros1_) return {p, n};
  if (p[n - 1] != '\0') {
    pos_ -= n;
    Fail(what, n, Problem::kValue);  // not NUL-terminated: the layout does not match
    return {};
  }
  return {p, n - 1};
}

uint32_t MessageReader::SequenceLength(const char* what, size_t min_element_bytes) {
  const uint32_t n = U32(what);
  if (!ok()) return 0;
  if (min_element_bytes > 0 && n > remaining() / min_element_bytes) {
    Fail(what, static_cast<size_t>(n) * min_element_bytes);
    return 0;
  }
  return n;
}

std::span<const uint8_t> MessageReader::Bytes(size_t n, const char* what) {
  if (!Need(n, what)) return {};
  const auto out = bytes_.subspan(pos_, n);
  pos_ += n;
  return out;
}

int64_t MessageReader::Time(const char* what) {
  const uint32_t sec = U32(what);
  const uint32_t nsec = U32(what);
  if (!ok()) return 0;
  if (nsec >= kNsPerS) {
    pos_ -= 4;
    Fail(what, 4, Problem::kValue);  // nanoseconds ≥ 10⁹
    return 0;
  }
  // ROS 2 seconds are int32, ROS 1 seconds uint32.
  const int64_t s =
      ros1_ ? static_cast<int64_t>(sec) : static_cast<int64_t>(static_cast<int32_t>(sec));
  return s * kNsPerS + nsec;
}

RosHeader MessageReader::Header() {
  RosHeader h;
  if (ros1_) U32("header.seq");
  h.stamp_ns = Time("header.stamp");
  h.frame_id = String("header.frame_id");
  return h;
}

}  // namespace swlio::drivers::bag
