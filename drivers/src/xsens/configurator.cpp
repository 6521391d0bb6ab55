// Xsens configure-on-start handshake (MT0101P: GoToConfig, ReqDID, SetOutputConfiguration,
// SetBaudrate, GoToMeasurement and their acknowledgements, Error 0x42). Pure state machine.

#include "swlio/drivers/xsens/configurator.h"

#include <algorithm>

#include "swlio/drivers/xsens/mtdata2.h"

namespace swlio::drivers::xsens {

XsensConfiguratorOptions ConfiguratorOptionsFromConfig(const ImuConfig& config) {
  XsensConfiguratorOptions o;
  o.reply_timeout_ns = config.reply_timeout_ms * 1'000'000;
  o.attempts = std::max<int64_t>(1, config.configure_retries);
  const auto rate = static_cast<uint16_t>(std::clamp<int64_t>(config.output_rate_hz, 1, 0xFFFE));
  const XsensOutputItem items[] = {
      {xdi::kPacketCounter, kXsensRateMax}, {xdi::kSampleTimeFine, kXsensRateMax},
      {xdi::kStatusWord, kXsensRateMax},    {xdi::kQuaternion, rate},
      {xdi::kAcceleration, rate},           {xdi::kRateOfTurn, rate},
  };
  o.output_count = std::size(items);
  std::copy(std::begin(items), std::end(items), o.outputs.begin());
  return o;
}

const char* ToString(XsensConfigStep step) {
  switch (step) {
    case XsensConfigStep::kIdle:
      return "idle";
    case XsensConfigStep::kGoToConfig:
      return "GoToConfig";
    case XsensConfigStep::kReqDid:
      return "ReqDID";
    case XsensConfigStep::kSetOutputConfiguration:
      return "SetOutputConfiguration";
    case XsensConfigStep::kSetBaudrate:
      return "SetBaudrate";
    case XsensConfigStep::kGoToMeasurement:
      return "GoToMeasurement";
    case XsensConfigStep::kDone:
      return "done";
    case XsensConfigStep::kFailed:
      return "failed";
  }
  return "?";
}

const char* ToString(XsensConfigFailure failure) {
  switch (failure) {
    case XsensConfigFailure::kNone:
      return "none";
    case XsensConfigFailure::kTimeout:
      return "no acknowledgement (timeout)";
    case XsensConfigFailure::kDeviceError:
      return "device answered Error (0x42)";
    case XsensConfigFailure::kOutputMismatch:
      return "applied output configuration differs";
    case XsensConfigFailure::kBadRequest:
      return "request could not be built";
  }
  return "?";
}

XsensConfigurator::XsensConfigurator(const XsensConfiguratorOptions& options) : options_(options) {
  options_.attempts = std::max<int64_t>(1, options_.attempts);
  options_.output_count = std::min(options_.output_count, XsensConfiguratorOptions::kMaxOutputs);
}

void XsensConfigurator::Start(int64_t now_ns) {
  failure_ = XsensConfigFailure::kNone;
  last_error_code_.reset();
  device_id_.reset();
  Enter(XsensConfigStep::kGoToConfig, now_ns);
}

void XsensConfigurator::Enter(XsensConfigStep step, int64_t now_ns) {
  step_ = step;
  attempts_used_ = 0;
  Send(now_ns);
}

void XsensConfigurator::Send(int64_t now_ns) {
  const std::span<uint8_t> out(tx_);
  switch (step_) {
    case XsensConfigStep::kGoToConfig:
      tx_size_ = BuildGoToConfig(out);
      break;
    case XsensConfigStep::kReqDid:
      tx_size_ = BuildReqDid(out);
      break;
    case XsensConfigStep::kSetOutputConfiguration:
      tx_size_ = BuildSetOutputConfiguration({options_.outputs.data(), options_.output_count}, out);
      break;
    case XsensConfigStep::kSetBaudrate:
      tx_size_ = BuildSetBaudrate(*options_.set_baud, out);
      break;
    case XsensConfigStep::kGoToMeasurement:
      tx_size_ = BuildGoToMeasurement(out);
      break;
    default:
      return;
  }
  if (tx_size_ == 0) {
    Fail(XsensConfigFailure::kBadRequest);
    return;
  }
  if (attempts_used_ > 0) ++stats_.retries;
  ++attempts_used_;
  ++stats_.sent;
  tx_pending_ = true;
  deadline_ns_ = now_ns + options_.reply_timeout_ns;
}

void XsensConfigurator::Advance(int64_t now_ns) {
  switch (step_) {
    case XsensConfigStep::kGoToConfig:
      Enter(XsensConfigStep::kReqDid, now_ns);
      return;
    case XsensConfigStep::kReqDid:
      Enter(XsensConfigStep::kSetOutputConfiguration, now_ns);
      return;
    case XsensConfigStep::kSetOutputConfiguration:
      Enter(options_.set_baud ? XsensConfigStep::kSetBaudrate : XsensConfigStep::kGoToMeasurement,
            now_ns);
      return;
    case XsensConfigStep::kSetBaudrate:
      Enter(XsensConfigStep::kGoToMeasurement, now_ns);
      return;
    case XsensConfigStep::kGoToMeasurement:
      step_ = XsensConfigStep::kDone;
      tx_pending_ = false;
      return;
    default:
      return;
  }
}

void XsensConfigurator::Fail(XsensConfigFailure why) {
  failed_step_ = step_;
  failure_ = why;
  step_ = XsensConfigStep::kFailed;
  tx_pending_ = false;
}

void XsensConfigurator::AttemptFailed(XsensConfigFailure why, int64_t now_ns) {
  if (attempts_used_ >= options_.attempts) {
    Fail(why);
    return;
  }
  Send(now_ns);
}

uint8_t XsensConfigurator::ExpectedAck() const {
  switch (step_) {
    case XsensConfigStep::kGoToConfig:
      return mid::kGoToConfigAck;
    case XsensConfigStep::kReqDid:
      return mid::kDeviceId;
    case XsensConfigStep::kSetOutputConfiguration:
      return mid::kOutputConfiguration;
    case XsensConfigStep::kSetBaudrate:
      return mid::kSetBaudrateAck;
    case XsensConfigStep::kGoToMeasurement:
      return mid::kGoToMeasurementAck;
    default:
      return mid::kError;  // never matched: Error is handled first
  }
}

bool XsensConfigurator::OutputEchoMatches(std::span<const uint8_t> payload) const {
  std::array<XsensOutputItem, XsensConfiguratorOptions::kMaxOutputs> got;
  const std::optional<size_t> n = ParseOutputConfiguration(payload, got);
  if (!n || *n != options_.output_count) return false;
  // Order-insensitive: every requested (XDI, rate) must be in the applied configuration.
  const auto applied_end = got.begin() + static_cast<std::ptrdiff_t>(*n);
  for (size_t i = 0; i < options_.output_count; ++i) {
    if (std::find(got.begin(), applied_end, options_.outputs[i]) == applied_end) return false;
  }
  return true;
}

void XsensConfigurator::OnFrame(const XbusFrame& frame, int64_t now_ns) {
  const bool waiting = step_ != XsensConfigStep::kIdle && step_ != XsensConfigStep::kDone &&
                       step_ != XsensConfigStep::kFailed;
  if (!waiting) {
    ++stats_.ignored_frames;
    return;
  }
  if (frame.mid == mid::kError) {
    ++stats_.errors;
    last_error_code_ = ParseErrorCode(frame.payload);
    AttemptFailed(XsensConfigFailure::kDeviceError, now_ns);
    return;
  }
  if (frame.mid != ExpectedAck()) {
    ++stats_.ignored_frames;
    return;
  }
  if (step_ == XsensConfigStep::kReqDid) device_id_ = ParseDeviceId(frame.payload);
  if (step_ == XsensConfigStep::kSetOutputConfiguration && !OutputEchoMatches(frame.payload)) {
    Fail(XsensConfigFailure::kOutputMismatch);
    return;
  }
  Advance(now_ns);
}

void XsensConfigurator::OnTick(int64_t now_ns) {
  const bool waiting = step_ != XsensConfigStep::kIdle && step_ != XsensConfigStep::kDone &&
                       step_ != XsensConfigStep::kFailed;
  if (!waiting || now_ns < deadline_ns_) return;
  ++stats_.timeouts;
  AttemptFailed(XsensConfigFailure::kTimeout, now_ns);
}

}  // namespace swlio::drivers::xsens
