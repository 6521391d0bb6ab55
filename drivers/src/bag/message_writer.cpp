// XCDR1 little-endian and ROS 1 message writer (message_writer.h; rules in message_reader.h).

#include "swlio/drivers/bag/message_writer.h"

#include <bit>

#include "swlio/drivers/bag/message_reader.h"  // kNsPerS

namespace swlio::drivers::bag {
namespace {

constexpr size_t kCdrOrigin = 4;

}  // namespace

MessageWriter::MessageWriter(MessageEncoding encoding) : ros1_(encoding == MessageEncoding::kRos1) {
  if (!ros1_) bytes_ = {0x00, 0x01, 0x00, 0x00};  // CDR_LE, options 0
}

void MessageWriter::Align(size_t n) {
  if (ros1_) return;
  while ((bytes_.size() - kCdrOrigin) % n != 0) bytes_.push_back(0);
}

void MessageWriter::Raw(uint64_t v, size_t n) {
  Align(n);
  for (size_t i = 0; i < n; ++i) bytes_.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

void MessageWriter::U16(uint16_t v) { Raw(v, 2); }
void MessageWriter::U32(uint32_t v) { Raw(v, 4); }
void MessageWriter::F32(float v) { Raw(std::bit_cast<uint32_t>(v), 4); }
void MessageWriter::F64(double v) { Raw(std::bit_cast<uint64_t>(v), 8); }

void MessageWriter::String(std::string_view s) {
  U32(static_cast<uint32_t>(s.size() + (ros1_ ? 0 : 1)));
  bytes_.insert(bytes_.end(), s.begin(), s.end());
  if (!ros1_) bytes_.push_back(0);
}

void MessageWriter::Time(int64_t t_ns) {
  int64_t sec = t_ns / kNsPerS;
  int64_t nsec = t_ns % kNsPerS;
  if (nsec < 0) {
    nsec += kNsPerS;
    --sec;
  }
  U32(static_cast<uint32_t>(sec));
  U32(static_cast<uint32_t>(nsec));
}

void MessageWriter::Header(int64_t stamp_ns, std::string_view frame_id) {
  if (ros1_) U32(0);
  Time(stamp_ns);
  String(frame_id);
}

void MessageWriter::PadToFour() {
  if (!ros1_) Align(4);
}

}  // namespace swlio::drivers::bag
