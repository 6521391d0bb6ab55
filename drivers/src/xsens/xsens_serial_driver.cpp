// Supervised Xsens MTi receiver over a serial port (see xsens_serial_driver.h). Protocol
// facts live in xbus.h, mtdata2.h and configurator.h (Xsens MT0101P).

#include "swlio/drivers/xsens/xsens_serial_driver.h"

#include <algorithm>
#include <utility>

namespace swlio::drivers::xsens {

XsensSerialDriver::XsensSerialDriver(const ImuConfig& config, XsensSampleSink sink)
    : configure_on_start_(config.configure_on_start),
      write_timeout_ns_(config.reply_timeout_ms * 1'000'000),
      port_(SerialPortOptions{config.device, config.baud, 200'000'000}),
      configurator_(ConfiguratorOptionsFromConfig(config)),
      decoder_(std::move(sink)) {}

const XsensDriverStats& XsensSerialDriver::stats() const {
  stats_view_ = stats_;
  XsensDriverStats& v = stats_view_;
  Accumulate(config_framer_.stats(), &v.config_framer);
  v.stream = decoder_.stats();
  v.framer = v.config_framer;
  Accumulate(v.stream.framer, &v.framer);
  return stats_view_;
}

void XsensSerialDriver::ResetConfigFramer() {
  config_framer_.Flush();
  Accumulate(config_framer_.stats(), &stats_.config_framer);
  config_framer_ = XbusFramer{};
}

void XsensSerialDriver::Connected(int64_t now_ns) {
  ResetConfigFramer();
  ++epoch_;
  configured_ = false;
  if (configure_on_start_) {
    configurator_.Start(now_ns);
    state_ = XsensDriverState::kConfigure;
    Transmit();
  } else {
    state_ = XsensDriverState::kStream;
  }
}

void XsensSerialDriver::Disconnected() {
  ResetConfigFramer();
  // The old stream's partial frame counts as skipped now; a hand-over's decoder drops it when
  // the next epoch's bytes arrive.
  decoder_.Restart();
  state_ = XsensDriverState::kOpen;
}

void XsensSerialDriver::Transmit() {
  const std::span<const uint8_t> tx = configurator_.PendingTx();
  if (tx.empty()) return;
  // A failed write is treated like a lost request: the configurator's timeout retries it.
  port_.Write(tx, write_timeout_ns_);
  configurator_.MarkSent();
}

XsensDriverState XsensSerialDriver::Poll(int64_t timeout_ns) {
  if (state_ == XsensDriverState::kOpen && port_.is_open()) Connected(MonotonicNowNs());
  if (state_ == XsensDriverState::kConfigure) {
    // Never sleep past the reply deadline.
    timeout_ns =
        std::min(timeout_ns, std::max<int64_t>(0, configurator_.deadline_ns() - MonotonicNowNs()));
  }
  const SerialRead r = port_.Read(rx_, timeout_ns);
  switch (r.status) {
    case SerialReadStatus::kClosed:
      if (state_ != XsensDriverState::kOpen) Disconnected();
      return state_;
    case SerialReadStatus::kReopened:
      Connected(r.t_host_ns);
      return state_;
    case SerialReadStatus::kData:
      last_read_ns_ = r.t_host_ns;
      if (raw_sink_) raw_sink_({rx_.data(), r.bytes}, r.t_host_ns);
      Process({rx_.data(), r.bytes}, r.t_host_ns);
      break;
    case SerialReadStatus::kTimeout:
      break;
  }
  if (state_ == XsensDriverState::kConfigure) {
    configurator_.OnTick(MonotonicNowNs());
    Transmit();
    if (configurator_.failed()) {
      ++stats_.config_failures;
      stats_.last_config_failure = configurator_.failure();
      stats_.last_failed_step = configurator_.failed_step();
      state_ = XsensDriverState::kStream;
      Stream(config_framer_.TakeBuffered(), last_read_ns_);  // a partial frame, if any
    }
  }
  return state_;
}

void XsensSerialDriver::Process(std::span<const uint8_t> bytes, int64_t t_host_ns) {
  if (state_ == XsensDriverState::kConfigure) {
    Configure(bytes, t_host_ns);
  } else {
    Stream(bytes, t_host_ns);
  }
}

void XsensSerialDriver::Configure(std::span<const uint8_t> bytes, int64_t t_host_ns) {
  XbusFrame frame;
  while (!bytes.empty() && state_ == XsensDriverState::kConfigure) {
    bytes = bytes.subspan(config_framer_.Feed(bytes));
    while (state_ == XsensDriverState::kConfigure && config_framer_.Next(&frame)) {
      configurator_.OnFrame(frame, t_host_ns);
      Transmit();
      if (configurator_.done()) {
        ++stats_.configurations;
        configured_ = true;
        state_ = XsensDriverState::kStream;
      }
    }
  }
  if (state_ != XsensDriverState::kStream) return;
  // The device streams right after its GoToMeasurement acknowledgement, often in the same
  // read: what follows the acknowledgement is the stream's first bytes.
  Stream(config_framer_.TakeBuffered(), t_host_ns);
  Stream(bytes, t_host_ns);
}

void XsensSerialDriver::Stream(std::span<const uint8_t> bytes, int64_t t_host_ns) {
  if (bytes.empty()) return;
  if (handover_) {
    handover_(bytes, t_host_ns, epoch_);
  } else {
    decoder_.Process(bytes, t_host_ns, epoch_);
  }
}

}  // namespace swlio::drivers::xsens
