#pragma once
/// @file
/// Configure-on-start handshake for an Xsens MTi as a pure state machine (no I/O, no clock):
///   GoToConfig → ReqDID → SetOutputConfiguration → [SetBaudrate] → GoToMeasurement → done.
/// Each step sends one request and waits for its acknowledgement (request MID + 1, MT0101P
/// "Message usage"). A missing reply after `reply_timeout_ns` or an Error (0x42) costs one
/// attempt; after `attempts` attempts the handshake fails and says at which step and why.
/// MTData2 and any other unrelated frames arriving meanwhile (the device may still stream
/// while switching to Config State) are ignored. Time is passed in as int64 ns.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "swlio/drivers/imu_config.h"
#include "swlio/drivers/xsens/xbus.h"
#include "swlio/drivers/xsens/xbus_messages.h"

namespace swlio::drivers::xsens {

struct XsensConfiguratorOptions {
  static constexpr size_t kMaxOutputs = 32;
  int64_t reply_timeout_ns = 500'000'000;
  int64_t attempts = 3;  ///< tries per message, ≥ 1
  std::array<XsensOutputItem, kMaxOutputs> outputs{};
  size_t output_count = 0;
  /// When set, SetBaudrate is sent (it takes effect after the device resets; the caller must
  /// reopen the port at the new rate).
  std::optional<int64_t> set_baud;
};

/// Options from the daemon's ImuConfig: timeout, retries and the output list (PacketCounter,
/// SampleTimeFine, StatusWord at every sample; Quaternion, Acceleration, RateOfTurn in Float32
/// ENU at `output_rate_hz`).
XsensConfiguratorOptions ConfiguratorOptionsFromConfig(const ImuConfig& config);

enum class XsensConfigStep : uint8_t {
  kIdle,
  kGoToConfig,
  kReqDid,
  kSetOutputConfiguration,
  kSetBaudrate,
  kGoToMeasurement,
  kDone,
  kFailed,
};
const char* ToString(XsensConfigStep step);

enum class XsensConfigFailure : uint8_t {
  kNone,
  kTimeout,         ///< no acknowledgement after every attempt
  kDeviceError,     ///< Error (0x42) on every attempt
  kOutputMismatch,  ///< the applied configuration differs from the request (order ignored)
  kBadRequest,      ///< a request could not be built (e.g. unknown baud rate)
};
const char* ToString(XsensConfigFailure failure);

struct XsensConfiguratorStats {
  uint64_t sent = 0;
  uint64_t retries = 0;
  uint64_t timeouts = 0;
  uint64_t errors = 0;  ///< Error (0x42) messages received
  uint64_t ignored_frames = 0;
};

class XsensConfigurator {
 public:
  explicit XsensConfigurator(const XsensConfiguratorOptions& options);

  /// Begins the handshake; the first request becomes pending.
  void Start(int64_t now_ns);
  /// Feeds a frame received from the device.
  void OnFrame(const XbusFrame& frame, int64_t now_ns);
  /// Advances time: retries or fails on timeout.
  void OnTick(int64_t now_ns);

  /// The request to write now (empty when none). Call MarkSent() after writing it.
  std::span<const uint8_t> PendingTx() const {
    return tx_pending_ ? std::span<const uint8_t>(tx_.data(), tx_size_)
                       : std::span<const uint8_t>{};
  }
  void MarkSent() { tx_pending_ = false; }

  XsensConfigStep step() const { return step_; }
  bool done() const { return step_ == XsensConfigStep::kDone; }
  bool failed() const { return step_ == XsensConfigStep::kFailed; }
  XsensConfigFailure failure() const { return failure_; }
  XsensConfigStep failed_step() const { return failed_step_; }
  std::optional<uint8_t> last_error_code() const { return last_error_code_; }
  std::optional<uint64_t> device_id() const { return device_id_; }
  /// Time by which the current step's reply is due (for the caller's poll timeout).
  int64_t deadline_ns() const { return deadline_ns_; }
  const XsensConfiguratorStats& stats() const { return stats_; }

 private:
  void Enter(XsensConfigStep step, int64_t now_ns);
  void Send(int64_t now_ns);
  void Advance(int64_t now_ns);
  void AttemptFailed(XsensConfigFailure why, int64_t now_ns);
  void Fail(XsensConfigFailure why);
  bool OutputEchoMatches(std::span<const uint8_t> payload) const;
  uint8_t ExpectedAck() const;

  XsensConfiguratorOptions options_;
  XsensConfigStep step_ = XsensConfigStep::kIdle;
  XsensConfigStep failed_step_ = XsensConfigStep::kIdle;
  XsensConfigFailure failure_ = XsensConfigFailure::kNone;
  int64_t attempts_used_ = 0;
  int64_t deadline_ns_ = 0;
  std::optional<uint8_t> last_error_code_;
  std::optional<uint64_t> device_id_;
  std::array<uint8_t, 4 * XsensConfiguratorOptions::kMaxOutputs + 8> tx_{};
  size_t tx_size_ = 0;
  bool tx_pending_ = false;
  XsensConfiguratorStats stats_;
};

}  // namespace swlio::drivers::xsens
