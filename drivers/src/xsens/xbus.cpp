// Xbus framer and frame encoder. Protocol: Xsens MT0101P "MT Low Level Communication
// Protocol Documentation", message structure (see xbus.h for the summary).

#include "swlio/drivers/xsens/xbus.h"

#include <algorithm>
#include <cstring>

#include "swlio/drivers/bytes.h"

namespace swlio::drivers::xsens {

uint8_t XbusSum(std::span<const uint8_t> bytes) {
  uint32_t sum = 0;
  for (const uint8_t b : bytes) sum += b;
  return static_cast<uint8_t>(sum);
}

size_t XbusFramer::Feed(std::span<const uint8_t> data) {
  if (kBufferSize - end_ < data.size()) Compact();
  const size_t n = std::min(data.size(), kBufferSize - end_);
  if (n > 0) std::memcpy(buf_ + end_, data.data(), n);
  end_ += n;
  stats_.bytes_in += n;
  return n;
}

void XbusFramer::Compact() {
  if (begin_ == 0) return;
  const size_t live = end_ - begin_;
  if (live > 0) std::memmove(buf_, buf_ + begin_, live);
  begin_ = 0;
  end_ = live;
}

void XbusFramer::Skip(size_t n) {
  begin_ += n;
  stats_.skipped_bytes += n;
}

bool XbusFramer::Next(XbusFrame* frame) {
  for (;;) {
    // Hunt for the preamble; everything before it is garbage.
    const uint8_t* start = buf_ + begin_;
    const uint8_t* pre =
        static_cast<const uint8_t*>(std::memchr(start, kXbusPreamble, end_ - begin_));
    if (pre == nullptr) {
      Skip(end_ - begin_);
      begin_ = end_ = 0;
      return false;
    }
    Skip(static_cast<size_t>(pre - start));
    const size_t avail = end_ - begin_;
    if (avail < 4) return false;
    const uint8_t* p = buf_ + begin_;
    if (p[1] != kXbusMasterBid) {
      ++stats_.bad_bid;
      Skip(1);
      continue;
    }
    size_t header = 4;
    size_t len = p[3];
    if (len == kXbusExtendedLen) {
      if (avail < 6) return false;
      header = 6;
      len = bytes::ReadU16Be(p + 4);
      if (len > kXbusMaxPayload) {
        ++stats_.oversize;
        Skip(1);
        continue;
      }
    }
    const size_t total = header + len + 1;
    if (avail < total) {
      // Make room so that the whole frame fits once the rest arrives.
      if (begin_ + total > kBufferSize) Compact();
      return false;
    }
    if (XbusSum({p + 1, total - 1}) != 0) {
      ++stats_.checksum_errors;
      Skip(1);
      continue;
    }
    frame->bid = p[1];
    frame->mid = p[2];
    frame->payload = {p + header, len};
    frame->frame_bytes = total;
    begin_ += total;
    ++stats_.frames;
    stats_.bytes_in_frames += total;
    return true;
  }
}

void XbusFramer::Flush() {
  Skip(end_ - begin_);
  begin_ = end_ = 0;
}

std::span<const uint8_t> XbusFramer::TakeBuffered() {
  const std::span<const uint8_t> rest{buf_ + begin_, end_ - begin_};
  stats_.bytes_in -= rest.size();
  begin_ = end_ = 0;
  return rest;
}

size_t EncodeXbusFrame(uint8_t mid, std::span<const uint8_t> payload, std::span<uint8_t> out) {
  if (payload.size() > kXbusMaxPayload) return 0;
  const bool extended = payload.size() >= kXbusExtendedLen;
  const size_t header = extended ? 6 : 4;
  const size_t total = header + payload.size() + 1;
  if (out.size() < total) return 0;
  uint8_t* p = out.data();
  p[0] = kXbusPreamble;
  p[1] = kXbusMasterBid;
  p[2] = mid;
  if (extended) {
    p[3] = kXbusExtendedLen;
    bytes::WriteU16Be(p + 4, static_cast<uint16_t>(payload.size()));
  } else {
    p[3] = static_cast<uint8_t>(payload.size());
  }
  if (!payload.empty()) std::memcpy(p + header, payload.data(), payload.size());
  p[total - 1] = static_cast<uint8_t>(0x100 - XbusSum({p + 1, total - 2}));
  return total;
}

}  // namespace swlio::drivers::xsens
