#pragma once
/// @file
/// Supervised Xsens MTi receiver: SerialPort + XbusFramer + XsensConfigurator +
/// XsensStreamDecoder, as the state machine OPEN → CONFIGURE → STREAM (→ OPEN when the device
/// vanishes).
///
/// - OPEN: waits for the serial device (re-opened automatically by SerialPort).
/// - CONFIGURE (when `configure_on_start`): runs the handshake (GoToConfig, ReqDID,
///   SetOutputConfiguration, GoToMeasurement) on the polling thread. If it fails, the failure
///   is counted and kept, and the driver streams whatever the device sends with its stored
///   configuration.
/// - STREAM: the bytes read from the handshake's end on go to the stream decoder, which hands
///   every MTData2 message to the sink with the host time of the read that completed it
///   (CLOCK_MONOTONIC ns) and counts other messages by MID class. With a hand-over set
///   (SetStreamHandover), the driver decodes nothing while streaming: the bytes go to the
///   hand-over with their read time and the port's open epoch, for an XsensStreamDecoder on
///   another thread.
/// Every open starts a new epoch: the decoder drops the old stream's partial frame and forgets
/// its PacketCounter there, and the device is configured again.
/// Meant to be driven by one rx thread calling Poll(); no allocation after construction.

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <utility>

#include "swlio/drivers/imu_config.h"
#include "swlio/drivers/serial_port.h"
#include "swlio/drivers/xsens/configurator.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"
#include "swlio/drivers/xsens/xsens_stream_decoder.h"

namespace swlio::drivers::xsens {

/// Receives every chunk of bytes read from the port, before framing, with its read time (a
/// recorder keeps them for bit-exact replay).
using XsensRawSink = std::function<void(std::span<const uint8_t> bytes, int64_t t_host_ns)>;
/// Receives the stream's bytes instead of the driver's own decoder, in read order, with the
/// read's host time and the port's open epoch (the arguments of XsensStreamDecoder::Process).
using XsensStreamHandover =
    std::function<void(std::span<const uint8_t> bytes, int64_t t_host_ns, uint32_t epoch)>;

enum class XsensDriverState : uint8_t { kOpen, kConfigure, kStream };

struct XsensDriverStats {
  /// The driver's own decoder's counters: zero with a hand-over set (its `framer` counts the
  /// stream only; `framer` below adds the handshakes').
  XsensStreamStats stream;
  uint64_t configurations = 0;   ///< successful handshakes
  uint64_t config_failures = 0;  ///< failed handshakes
  XsensConfigFailure last_config_failure = XsensConfigFailure::kNone;
  XsensConfigStep last_failed_step = XsensConfigStep::kIdle;
  XbusFramerStats framer;         ///< handshakes and stream, accumulated over reconnects
  XbusFramerStats config_framer;  ///< of those: the handshakes'
};

class XsensSerialDriver {
 public:
  XsensSerialDriver(const ImuConfig& config, XsensSampleSink sink);

  /// One step: waits up to `timeout_ns` for bytes and processes them. Returns the state after.
  XsensDriverState Poll(int64_t timeout_ns);

  XsensDriverState state() const { return state_; }
  /// Sets (or clears, with an empty function) the raw-bytes sink. Call before polling starts.
  void SetRawSink(XsensRawSink sink) { raw_sink_ = std::move(sink); }
  /// Sends the stream's bytes to `handover` instead of decoding them (see the file comment);
  /// an empty function decodes them here again. Call before polling starts.
  void SetStreamHandover(XsensStreamHandover handover) { handover_ = std::move(handover); }
  bool configured() const { return configured_; }
  const XsensDriverStats& stats() const;
  /// The port's open number: increments at every open (the first open is 1).
  uint32_t epoch() const { return epoch_; }
  /// Bytes of the Xbus frame whose sample the sink is receiving (header, payload, checksum):
  /// its transmission time at the line rate is the fixed part of the receive latency.
  size_t last_frame_bytes() const { return decoder_.last_frame_bytes(); }
  const SerialPort& port() const { return port_; }
  const XsensConfigurator& configurator() const { return configurator_; }

 private:
  void Connected(int64_t now_ns);
  void Disconnected();
  void Process(std::span<const uint8_t> bytes, int64_t t_host_ns);
  void Configure(std::span<const uint8_t> bytes, int64_t t_host_ns);
  void Stream(std::span<const uint8_t> bytes, int64_t t_host_ns);
  void Transmit();
  void ResetConfigFramer();

  bool configure_on_start_;
  int64_t write_timeout_ns_;
  SerialPort port_;
  XsensConfigurator configurator_;
  XsensRawSink raw_sink_;
  XsensStreamHandover handover_;
  XbusFramer config_framer_;  ///< frames the handshake's replies
  XsensStreamDecoder decoder_;
  XsensDriverState state_ = XsensDriverState::kOpen;
  bool configured_ = false;
  uint32_t epoch_ = 0;
  int64_t last_read_ns_ = 0;
  std::array<uint8_t, 4096> rx_{};
  XsensDriverStats stats_;  ///< config_framer: of the handshakes before the current one
  mutable XsensDriverStats stats_view_;
};

}  // namespace swlio::drivers::xsens
