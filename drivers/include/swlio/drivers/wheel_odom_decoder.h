#pragma once
/// @file
/// Wheel-odometry decoder for chassis CAN frames, with the signal layout taken from
/// `CanConfig` (see can_config.h for the DBC bit-numbering conventions). Pure: no I/O, no
/// allocation after construction; every frame it cannot use is counted, never fatal.
///
/// Differential drive (mode wheel_speeds), with wheel rim speeds v_l, v_r in m/s (a speed
/// in rad/s is multiplied by the wheel radius first) and track width b:
///   linear velocity  v = (v_r + v_l) / 2
///   yaw rate         ω = (v_r − v_l) / b          (CCW positive, seen from above)
/// Mode twist reads v and ω directly.

#include <array>
#include <cstdint>
#include <optional>

#include "swlio/core/config_issue.h"
#include "swlio/drivers/can_config.h"
#include "swlio/drivers/can_frame.h"

namespace swlio::drivers {

/// One odometry measurement of the chassis body frame (x forward, z up).
struct WheelOdomSample {
  int64_t t_ns = 0;                  ///< host receive time of the frame that completed it
  double linear_velocity_mps = 0.0;  ///< forward speed
  double yaw_rate_radps = 0.0;       ///< about z, CCW positive
  bool has_wheel_speeds = false;     ///< true in mode wheel_speeds
  double left_wheel_mps = 0.0;       ///< rim speed of the left wheel (wheel_speeds only)
  double right_wheel_mps = 0.0;      ///< rim speed of the right wheel (wheel_speeds only)
};

struct WheelOdomCounters {
  uint64_t frames = 0;            ///< every frame given to Decode()
  uint64_t frames_used = 0;       ///< frames that carried at least one signal
  uint64_t unknown_id = 0;        ///< no signal uses this identifier
  uint64_t bad_dlc = 0;           ///< too short for a signal, or not the configured DLC
  uint64_t remote_or_error = 0;   ///< remote (RTR) or error frames with a known id, ignored
  uint64_t unpaired_dropped = 0;  ///< a value replaced or expired before its partner arrived
  uint64_t samples = 0;           ///< samples produced
};

/// One signal compiled for extraction.
struct CompiledCanSignal {
  uint32_t id = 0;
  bool extended = false;
  bool motorola = false;
  bool is_signed = false;
  uint8_t length_bits = 0;
  uint8_t shift = 0;      ///< right shift of the 64-bit payload word (see Extract)
  uint8_t min_dlc = 0;    ///< bytes needed to hold the field
  uint8_t exact_dlc = 0;  ///< 0 = any DLC ≥ min_dlc
  double scale = 1.0;
  double offset = 0.0;
};

/// Compiles a validated signal; std::nullopt when `Validate()` reports anything.
std::optional<CompiledCanSignal> CompileCanSignal(const CanSignalConfig& config);

/// The physical value of `signal` in `frame`, which must hold at least `signal.min_dlc` bytes.
double ExtractCanSignal(const CompiledCanSignal& signal, const CanFrame& frame);

class WheelOdomDecoder {
 public:
  /// A decoder for a layout that passes `config.ValidateLayout()`, else std::nullopt with the
  /// issues in `*issues` (when given).
  static std::optional<WheelOdomDecoder> Create(const CanConfig& config,
                                                ConfigIssues* issues = nullptr);

  /// Feeds one received frame (host time `t_ns`); returns a sample when this frame completes
  /// one. Frames of other identifiers, remote/error frames and wrong lengths are counted.
  std::optional<WheelOdomSample> Decode(const CanFrame& frame, int64_t t_ns);

  const WheelOdomCounters& counters() const { return counters_; }
  /// The (up to two) distinct identifiers the layout uses, for receive filters.
  int NumIds() const { return num_ids_; }
  const CompiledCanSignal& IdSignal(int i) const {
    return signals_[static_cast<size_t>(ids_[static_cast<size_t>(i)])];
  }

 private:
  WheelOdomDecoder() = default;
  std::optional<WheelOdomSample> MakeSample(int64_t t_ns);

  std::array<CompiledCanSignal, 2> signals_{};  ///< [0] left/linear, [1] right/angular
  std::array<double, 2> value_{};
  std::array<int64_t, 2> value_t_ns_{};
  std::array<bool, 2> fresh_{};
  std::array<int, 2> ids_{};  ///< indices into signals_ of the distinct identifiers
  int num_ids_ = 0;
  bool wheel_speeds_ = true;
  double speed_factor_ = 1.0;  ///< wheel radius for rad/s inputs, else 1
  double track_width_m_ = 0.5;
  int64_t max_pair_skew_ns_ = 0;
  WheelOdomCounters counters_;
};

}  // namespace swlio::drivers
