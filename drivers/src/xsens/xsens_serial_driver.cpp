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
      sink_(std::move(sink)) {}

const XsensDriverStats& XsensSerialDriver::stats() const {
  stats_view_ = stats_;
  const XbusFramerStats& f = framer_.stats();
  XbusFramerStats& v = stats_view_.framer;
  v.bytes_in += f.bytes_in;
  v.frames += f.frames;
  v.bytes_in_frames += f.bytes_in_frames;
  v.checksum_errors += f.checksum_errors;
  v.skipped_bytes += f.skipped_bytes;
  v.oversize += f.oversize;
  v.bad_bid += f.bad_bid;
  return stats_view_;
}

void XsensSerialDriver::AccumulateFramer() {
  framer_.Flush();
  stats_.framer = stats().framer;
  framer_ = XbusFramer{};
}

void XsensSerialDriver::Connected(int64_t now_ns) {
  AccumulateFramer();
  last_counter_.reset();
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
  AccumulateFramer();
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
    }
  }
  return state_;
}

void XsensSerialDriver::Process(std::span<const uint8_t> bytes, int64_t t_host_ns) {
  size_t pos = 0;
  XbusFrame frame;
  while (pos < bytes.size()) {
    pos += framer_.Feed(bytes.subspan(pos));
    while (framer_.Next(&frame)) {
      if (state_ == XsensDriverState::kConfigure) {
        configurator_.OnFrame(frame, t_host_ns);
        Transmit();
        if (configurator_.done()) {
          ++stats_.configurations;
          configured_ = true;
          state_ = XsensDriverState::kStream;
        }
        continue;
      }
      OnStreamFrame(frame, t_host_ns);
    }
  }
}

void XsensSerialDriver::OnStreamFrame(const XbusFrame& frame, int64_t t_host_ns) {
  if (frame.mid != mid::kMtData2) {
    ++(frame.mid == mid::kError ? stats_.error_messages : stats_.other_messages);
    return;
  }
  if (DecodeMtData2(frame.payload, &sample_) != MtData2Status::kOk) ++stats_.truncated;
  ++stats_.samples;
  stats_.unknown_items += sample_.unknown_items;
  stats_.bad_size_items += sample_.bad_size_items;
  if (sample_.packet_counter) {
    const uint16_t c = *sample_.packet_counter;
    if (last_counter_) {
      const auto step = static_cast<uint16_t>(c - *last_counter_);
      if (step != 1) ++stats_.counter_gaps;
      // Forward jumps count as losses; repeats and backward jumps (device reset) do not.
      if (step > 1 && step < 0x8000) stats_.missing_packets += step - 1u;
    }
    last_counter_ = c;
  }
  last_frame_bytes_ = frame.frame_bytes;
  if (sink_) sink_(sample_, t_host_ns);
}

}  // namespace swlio::drivers::xsens
