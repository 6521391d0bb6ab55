#pragma once
/// @file
/// The can_rx thread (when `can.enabled`): reads the chassis' SocketCAN frames (CanReader: the
/// kernel filters them to the layout's identifiers and stamps them), decodes wheel odometry
/// (WheelOdomDecoder) for the health's rate and counters, pushes each frame to the recorder
/// and, when the window's wheel factor is on (estimator.window.wheel), each decoded sample to
/// the optimizer. No allocation after construction.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "swlio/core/types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/drivers/can_config.h"
#include "swlio/drivers/can_reader.h"
#include "swlio/drivers/wheel_odom_decoder.h"

namespace swlio::daemon {

struct CanRxCounters {
  uint64_t frames = 0;
  uint64_t odometry_samples = 0;  ///< decoded wheel-odometry samples
  uint64_t unknown_id = 0;
  uint64_t bad_frames = 0;  ///< wrong record size, wrong DLC, remote or error frames
  uint64_t read_errors = 0;
  bool closed = false;  ///< the interface went away
};

class CanRx {
 public:
  /// On `fd` (a CAN_RAW socket, or any fd carrying `struct can_frame` records; not owned).
  /// Nullptr with the layout's problems in `error` when the configuration cannot decode.
  static std::unique_ptr<CanRx> Create(const drivers::CanConfig& config,
                                       int fd,
                                       std::string* error);
  /// Also pushes every frame to `record` (the recorder's queue); call before Run.
  void RecordTo(SpscQueue<drivers::CanRxFrame>* record) { record_ = record; }
  /// Also pushes every decoded odometry sample to `wheel` (the optimizer's); call before Run.
  void SendTo(SpscQueue<WheelOdometry>* wheel) { wheel_ = wheel; }
  /// Reads until `stop` is set (or the peer closes), beating at least every 100 ms.
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  CanRxCounters counters() const;

 private:
  CanRx(int fd,
        std::span<const drivers::CanIdFilter> filters,
        const drivers::WheelOdomDecoder& decoder);
  void Publish(bool closed);

  drivers::CanReader reader_;
  drivers::WheelOdomDecoder decoder_;
  SpscQueue<drivers::CanRxFrame>* record_ = nullptr;
  SpscQueue<WheelOdometry>* wheel_ = nullptr;
  std::array<drivers::CanRxFrame, 32> frames_{};
  std::atomic<uint64_t> frames_n_{0}, samples_{0}, unknown_{0}, bad_{0}, errors_{0};
  std::atomic<bool> closed_{false};
};

}  // namespace swlio::daemon
