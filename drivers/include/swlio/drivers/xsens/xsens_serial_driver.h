#pragma once
/// @file
/// Supervised Xsens MTi receiver: SerialPort + XbusFramer + XsensConfigurator + MTData2
/// decoder, as the state machine OPEN → CONFIGURE → STREAM (→ OPEN when the device vanishes).
///
/// - OPEN: waits for the serial device (re-opened automatically by SerialPort).
/// - CONFIGURE (when `configure_on_start`): runs the handshake (GoToConfig, ReqDID,
///   SetOutputConfiguration, GoToMeasurement). If it fails, the failure is counted and kept,
///   and the driver streams whatever the device sends with its stored configuration.
/// - STREAM: every MTData2 message goes to the sink with the host time of the read that
///   completed it (CLOCK_MONOTONIC ns); other messages are counted by MID class.
/// After a disconnect the framer is reset and the device is configured again when it returns.
/// Meant to be driven by one rx thread calling Poll(); no allocation after construction.

#include <cstdint>
#include <functional>
#include <span>
#include <utility>

#include "swlio/drivers/imu_config.h"
#include "swlio/drivers/serial_port.h"
#include "swlio/drivers/xsens/configurator.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::drivers::xsens {

/// Receives each decoded MTData2 message and the host receive time of its last byte.
using XsensSampleSink = std::function<void(const MtData2Sample& sample, int64_t t_host_ns)>;
/// Receives every chunk of bytes read from the port, before framing, with its read time (a
/// recorder keeps them for bit-exact replay).
using XsensRawSink = std::function<void(std::span<const uint8_t> bytes, int64_t t_host_ns)>;

enum class XsensDriverState : uint8_t { kOpen, kConfigure, kStream };

struct XsensDriverStats {
  uint64_t samples = 0;          ///< MTData2 messages delivered
  uint64_t truncated = 0;        ///< MTData2 payloads with a truncated item (partially decoded)
  uint64_t unknown_items = 0;    ///< MTData2 items skipped (unknown XDI)
  uint64_t bad_size_items = 0;   ///< MTData2 items skipped (impossible size)
  uint64_t counter_gaps = 0;     ///< PacketCounter discontinuities
  uint64_t missing_packets = 0;  ///< packets lost according to PacketCounter
  uint64_t error_messages = 0;   ///< Error (0x42) seen while streaming
  uint64_t other_messages = 0;   ///< non-MTData2 messages seen while streaming
  uint64_t configurations = 0;   ///< successful handshakes
  uint64_t config_failures = 0;  ///< failed handshakes
  XsensConfigFailure last_config_failure = XsensConfigFailure::kNone;
  XsensConfigStep last_failed_step = XsensConfigStep::kIdle;
  XbusFramerStats framer;  ///< accumulated over reconnects
};

class XsensSerialDriver {
 public:
  XsensSerialDriver(const ImuConfig& config, XsensSampleSink sink);

  /// One step: waits up to `timeout_ns` for bytes and processes them. Returns the state after.
  XsensDriverState Poll(int64_t timeout_ns);

  XsensDriverState state() const { return state_; }
  /// Sets (or clears, with an empty function) the raw-bytes sink. Call before polling starts.
  void SetRawSink(XsensRawSink sink) { raw_sink_ = std::move(sink); }
  bool configured() const { return configured_; }
  const XsensDriverStats& stats() const;
  /// Bytes of the Xbus frame whose sample the sink is receiving (header, payload, checksum):
  /// its transmission time at the line rate is the fixed part of the receive latency.
  size_t last_frame_bytes() const { return last_frame_bytes_; }
  const SerialPort& port() const { return port_; }
  const XsensConfigurator& configurator() const { return configurator_; }

 private:
  void Connected(int64_t now_ns);
  void Disconnected();
  void Process(std::span<const uint8_t> bytes, int64_t t_host_ns);
  void OnStreamFrame(const XbusFrame& frame, int64_t t_host_ns);
  void Transmit();
  void AccumulateFramer();

  bool configure_on_start_;
  int64_t write_timeout_ns_;
  SerialPort port_;
  XsensConfigurator configurator_;
  XsensSampleSink sink_;
  XsensRawSink raw_sink_;
  XbusFramer framer_;
  MtData2Sample sample_;
  XsensDriverState state_ = XsensDriverState::kOpen;
  bool configured_ = false;
  std::optional<uint16_t> last_counter_;
  size_t last_frame_bytes_ = 0;
  std::array<uint8_t, 4096> rx_{};
  XsensDriverStats stats_;
  mutable XsensDriverStats stats_view_;
};

}  // namespace swlio::drivers::xsens
