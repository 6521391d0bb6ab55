#pragma once
/// @file
/// Xsens samples → IMU samples on the host clock: the SampleTimeFine clock model (10 kHz ticks,
/// wrapping every 2³² ticks ≈ 5 days), the one path live and replay share. The frame's
/// transmission time at the line rate (10 bits per byte, 8N1) is the fixed latency removed;
/// it is taken from the first frame.

#include <cstddef>
#include <cstdint>
#include <optional>

#include "swlio/core/types.h"
#include "swlio/drivers/clock_model.h"
#include "swlio/drivers/xsens/mtdata2.h"

namespace swlio::daemon {

/// One decoded MTData2 sample as ImuStage takes it (fixed size; before the clock model).
struct ImuRaw {
  int64_t t_rx_ns = 0;            ///< host receive time of the frame's last byte
  uint32_t sample_time_fine = 0;  ///< Xsens 10 kHz ticks, valid when has_sample_time_fine
  uint32_t frame_bytes = 0;       ///< Xbus frame size on the wire
  bool has_sample_time_fine = false;
  bool has_inertial = false;  ///< acceleration and rate of turn both present
  Eigen::Vector3d acc_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_radps = Eigen::Vector3d::Zero();
  /// The frame's GnssPvtData item (MTi-G-710 GNSS), mapped with the sample's time downstream.
  bool has_gnss_pvt = false;
  drivers::xsens::XsensGnssPvt gnss_pvt;
};

/// The fields ImuStage needs from a decoded sample.
ImuRaw ToImuRaw(const drivers::xsens::MtData2Sample& sample, int64_t t_rx_ns, size_t frame_bytes);

struct ImuStageCounters {
  uint64_t samples = 0;         ///< mapped to host time
  uint64_t no_sample_time = 0;  ///< dropped: the frame had no SampleTimeFine
  uint64_t incomplete = 0;      ///< dropped: acceleration or rate of turn missing or not finite
  uint64_t out_of_order = 0;    ///< dropped: host time not after the previous sample's
};

class ImuStage {
 public:
  /// `baud`: the serial line rate, for the transmission latency.
  explicit ImuStage(int64_t baud);

  /// Maps one sample to host time. Nullopt when dropped (counted).
  std::optional<ImuSample> Map(const ImuRaw& raw);

  const ImuStageCounters& counters() const { return counters_; }
  const drivers::ClockModelStats& clock() const { return clock_.stats(); }

 private:
  int64_t baud_;
  drivers::ClockModelConfig clock_config_;
  drivers::ClockModel clock_;
  bool latency_set_ = false;
  int64_t last_t_ns_ = 0;
  ImuStageCounters counters_;
};

}  // namespace swlio::daemon
