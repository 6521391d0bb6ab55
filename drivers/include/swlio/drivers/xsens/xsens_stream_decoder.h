#pragma once
/// @file
/// The streaming half of the Xsens receiver: Xbus framing (checksums, resynchronization),
/// MTData2 decoding and PacketCounter gap accounting over the bytes an MTi sends in
/// measurement mode. Pure: no I/O, no clock, no allocation after construction.
///
/// Bytes arrive in chunks of any split, each with the host time of the read(2) that returned
/// it; a sample takes the time of the chunk that completed its frame. Each chunk carries the
/// serial port's open epoch: when it changes (the device was unplugged and opened again), the
/// partial frame of the old stream is dropped (counted as skipped bytes) and the PacketCounter
/// forgotten before the chunk's bytes are framed, so a reconnect is neither a gap nor a
/// checksum error. The epoch travels with the bytes, so a reader thread can hand them over
/// through a queue that drops when full and the reset still happens at its place in the stream.
/// The XsensSerialDriver uses one on its own thread; the daemon's propagator thread owns one.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <utility>

#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::drivers::xsens {

/// Receives each decoded MTData2 message and the host receive time of its last byte.
using XsensSampleSink = std::function<void(const MtData2Sample& sample, int64_t t_host_ns)>;

struct XsensStreamStats {
  uint64_t samples = 0;          ///< MTData2 messages delivered
  uint64_t truncated = 0;        ///< MTData2 payloads with a truncated item (partially decoded)
  uint64_t unknown_items = 0;    ///< MTData2 items skipped (unknown XDI)
  uint64_t bad_size_items = 0;   ///< MTData2 items skipped (impossible size)
  uint64_t counter_gaps = 0;     ///< PacketCounter discontinuities
  uint64_t missing_packets = 0;  ///< packets lost according to PacketCounter
  uint64_t error_messages = 0;   ///< Error (0x42) seen while streaming
  uint64_t other_messages = 0;   ///< non-MTData2 messages seen while streaming
  uint64_t restarts = 0;         ///< new streams begun (epoch changes after the first chunk)
  XbusFramerStats framer;        ///< accumulated over restarts
};

class XsensStreamDecoder {
 public:
  explicit XsensStreamDecoder(XsensSampleSink sink = {}) : sink_(std::move(sink)) {}

  /// Sets the sink; before the first Process.
  void SetSink(XsensSampleSink sink) { sink_ = std::move(sink); }

  /// Frames and decodes `bytes`, read at `t_host_ns` (CLOCK_MONOTONIC ns) from the port's
  /// open number `epoch`; calls the sink for each MTData2 message it completes. Restart()s
  /// first when `epoch` differs from the previous chunk's.
  void Process(std::span<const uint8_t> bytes, int64_t t_host_ns, uint32_t epoch);

  /// Ends the current stream: its partial frame is counted as skipped and dropped, the
  /// PacketCounter forgotten. Counters are kept.
  void Restart();

  const XsensStreamStats& stats() const;
  /// Bytes of the Xbus frame whose sample the sink is receiving (header, payload, checksum):
  /// its transmission time at the line rate is the fixed part of the receive latency.
  size_t last_frame_bytes() const { return last_frame_bytes_; }

 private:
  void OnFrame(const XbusFrame& frame, int64_t t_host_ns);

  XsensSampleSink sink_;
  XbusFramer framer_;
  MtData2Sample sample_;
  std::optional<uint32_t> epoch_;
  std::optional<uint16_t> last_counter_;
  size_t last_frame_bytes_ = 0;
  XsensStreamStats stats_;  ///< framer: of the streams before the current one
  mutable XsensStreamStats stats_view_;
};

/// Adds `b`'s counts to `a`.
void Accumulate(const XbusFramerStats& b, XbusFramerStats* a);

}  // namespace swlio::drivers::xsens
