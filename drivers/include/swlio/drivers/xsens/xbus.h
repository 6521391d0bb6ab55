#pragma once
/// @file
/// Xbus framing for Xsens MTi devices (target: MTi-G-710).
///
/// Protocol summary (Xsens "MT Low Level Communication Protocol Documentation", document
/// MT0101P, section "Message structure"; also the MTi User Manual MT0605P §5.3.1):
///   PRE(0xFA) BID(0xFF) MID LEN [EXTLEN_HI EXTLEN_LO] DATA… CS
/// - PRE is always 0xFA; BID is 0xFF ("master device") for every MTi message.
/// - LEN 0…254 is the data length; LEN = 0xFF announces the extended form, where a 2-byte
///   big-endian length follows (Xsens' XsMessageHeader: "a length of 255 means extended
///   length is used"). swlio caps the data field at kXbusMaxPayload; a header announcing more
///   is treated as corrupt (counted as `oversize`).
/// - CS: all bytes after the preamble, checksum included, sum to 0 modulo 256.
/// - A request with MID m is acknowledged by MID m+1; MID 0x42 (Error) carries an error code.
/// All multi-byte fields are big-endian.

#include <cstddef>
#include <cstdint>
#include <span>

namespace swlio::drivers::xsens {

inline constexpr uint8_t kXbusPreamble = 0xFA;
inline constexpr uint8_t kXbusMasterBid = 0xFF;
inline constexpr uint8_t kXbusExtendedLen = 0xFF;
/// Largest data field accepted: swlio's own cap, several times an MTData2 message carrying
/// every item of the einride captures plus GNSS satellite info for 64 satellites (~600 B).
inline constexpr size_t kXbusMaxPayload = 2048;
/// PRE BID MID LEN EXTLEN(2) + data + CS.
inline constexpr size_t kXbusMaxFrame = 6 + kXbusMaxPayload + 1;

/// Message identifiers used by swlio (MT0101P, "Message listing").
namespace mid {
inline constexpr uint8_t kReqDid = 0x00;
inline constexpr uint8_t kDeviceId = 0x01;
inline constexpr uint8_t kGoToMeasurement = 0x10;
inline constexpr uint8_t kGoToMeasurementAck = 0x11;
inline constexpr uint8_t kSetBaudrate = 0x18;
inline constexpr uint8_t kSetBaudrateAck = 0x19;
inline constexpr uint8_t kGoToConfig = 0x30;
inline constexpr uint8_t kGoToConfigAck = 0x31;
inline constexpr uint8_t kMtData2 = 0x36;
inline constexpr uint8_t kWakeUp = 0x3E;
inline constexpr uint8_t kError = 0x42;
inline constexpr uint8_t kSetOutputConfiguration = 0xC0;
inline constexpr uint8_t kOutputConfiguration = 0xC1;
}  // namespace mid

/// One complete, checksum-valid Xbus message. `payload` points into the framer's buffer and
/// stays valid until the next call to `XbusFramer::Feed` or `XbusFramer::Next`.
struct XbusFrame {
  uint8_t bid = 0;
  uint8_t mid = 0;
  std::span<const uint8_t> payload;
  size_t frame_bytes = 0;  ///< whole message on the wire, preamble and checksum included
};

/// Counters of the framer. Invariant after `Flush()`: bytes_in = bytes_in_frames + skipped_bytes.
struct XbusFramerStats {
  uint64_t bytes_in = 0;
  uint64_t frames = 0;           ///< valid frames delivered
  uint64_t bytes_in_frames = 0;  ///< bytes of delivered frames
  uint64_t checksum_errors = 0;  ///< complete candidate frames whose checksum failed
  uint64_t skipped_bytes = 0;    ///< bytes that were not part of any valid frame
  uint64_t oversize = 0;         ///< headers announcing more than kXbusMaxPayload bytes
  uint64_t bad_bid = 0;          ///< 0xFA followed by a bus id other than 0xFF
};

/// Resynchronizing Xbus framer over a fixed internal buffer (no allocation).
///
/// Usage: `Feed()` bytes as they arrive (any split), then call `Next()` until it returns
/// false. A candidate frame whose checksum fails (or whose header is impossible) costs only
/// its preamble byte: scanning resumes at the next byte, so valid frames hidden behind a false
/// preamble are never lost. Leading bytes of a frame cut at the start of a stream are skipped.
class XbusFramer {
 public:
  /// Internal buffer: two maximal frames, so a full frame always fits after compaction.
  static constexpr size_t kBufferSize = 2 * kXbusMaxFrame;

  /// Copies up to `data.size()` bytes in; returns how many were taken. Fewer than offered
  /// means the buffer is full: call `Next()` until false, then feed the rest.
  size_t Feed(std::span<const uint8_t> data);

  /// Extracts the next valid frame; false when more bytes are needed.
  bool Next(XbusFrame* frame);

  /// Declares end of stream: bytes still buffered are counted as skipped and dropped.
  void Flush();

  /// Gives back the bytes buffered and not yet framed, as if they had never been fed (they
  /// leave `bytes_in`): for handing the rest of a stream to another framer when the protocol
  /// phase changes. The span stays valid until the next Feed.
  std::span<const uint8_t> TakeBuffered();

  /// Bytes buffered and not yet consumed.
  size_t buffered() const { return end_ - begin_; }
  const XbusFramerStats& stats() const { return stats_; }

 private:
  void Skip(size_t n);
  void Compact();

  uint8_t buf_[kBufferSize];
  size_t begin_ = 0;
  size_t end_ = 0;
  XbusFramerStats stats_;
};

/// Sum of `bytes` modulo 256.
uint8_t XbusSum(std::span<const uint8_t> bytes);

/// Writes a complete master message (BID 0xFF) for `mid` and `payload` into `out`; uses the
/// extended length form when the payload exceeds 254 bytes. Returns the frame size, or 0 when
/// `out` is too small or the payload exceeds kXbusMaxPayload.
size_t EncodeXbusFrame(uint8_t mid, std::span<const uint8_t> payload, std::span<uint8_t> out);

}  // namespace swlio::drivers::xsens
