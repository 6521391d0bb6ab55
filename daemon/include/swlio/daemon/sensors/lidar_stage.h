#pragma once
/// @file
/// LiDAR datagrams → sweeps on the host clock: the model's packet decoder, the sensor clock
/// model and the scan assembler, in that order. The one path both the live daemon (optimizer
/// thread) and the recording reader (replay, swlio-run) use, so replay decodes exactly as live.
///
/// Clock: every data packet's header time is observed against its host receive time; a sweep's
/// times are mapped with the model as it stands when the sweep completes (causal, as live).
/// The RS16 header time is the packet's first firing and the packet is sent after its last:
/// that span (23 firing sequences + 15 channel slots ≈ 1.32 ms, RS-LiDAR-16 manual §9.2 timing)
/// is the fixed latency removed. Datagrams as late as the socket's receive buffer can hold (a
/// starved reader's backlog) are not a clock jump unless that lasts as long (docs/scheduling.md).

#include <cstdint>
#include <memory>
#include <span>

#include "swlio/core/types.h"
#include "swlio/drivers/clock_model.h"
#include "swlio/drivers/lidar_config.h"
#include "swlio/drivers/lidar_decoder.h"
#include "swlio/drivers/scan_assembler.h"

namespace swlio::daemon {

struct LidarStageCounters {
  uint64_t data_packets = 0;  ///< decoded data packets
  uint64_t info_packets = 0;  ///< DIFOP (calibration, rpm) packets adopted
  uint64_t bad_packets = 0;   ///< wrong size, bad header or truncated: dropped
  uint64_t info_errors = 0;   ///< info packets the decoder refused
  uint64_t sweeps = 0;
  uint64_t partial_sweeps = 0;
  uint64_t missing_packets = 0;  ///< packets the assembler found missing inside sweeps
  /// Sweeps moved later by at most kMaxAbsorbedOverlapNs so that they start where the previous
  /// one ended (the clock model's re-fit had mapped them back): see LidarStage::Pop.
  uint64_t overlaps_absorbed = 0;
};

/// A sweep on the host clock with what the assembler knew about it.
struct HostSweep {
  /// t_start_ns host time; points' dt_ns from it on the sensor clock; t_end_ns = t_start_ns +
  /// the sweep's span on the sensor clock (the last point's time).
  Scan scan;
  int64_t host_rx_last_ns = 0;
  uint32_t missing_packets = 0;
};

class LidarStage {
 public:
  explicit LidarStage(const drivers::LidarConfig& config);
  ~LidarStage();
  LidarStage(const LidarStage&) = delete;
  LidarStage& operator=(const LidarStage&) = delete;

  /// One datagram (MSOP or DIFOP, told apart by content) with its host receive time.
  void Add(std::span<const uint8_t> payload, int64_t t_rx_ns);
  /// Closes the sweep in progress (end of a recording).
  void Flush();
  /// The oldest completed sweep, storage swapped with `out` (reuse one HostSweep: no
  /// allocation in steady state). False when none is ready.
  /// Each sweep's times are mapped with the clock model as it stands at its end. A re-fit
  /// between two sweeps can map the next one to start up to tens of µs before the previous one
  /// ended (seen on the first full sweep); the estimator would refuse it as out of order. Such
  /// an overlap of at most kMaxAbsorbedOverlapNs — far inside the model's error bound — is
  /// absorbed by moving the sweep to start at the previous end. A larger step back (a clock
  /// jump) is passed on as it is.
  bool Pop(HostSweep* out);
  static constexpr int64_t kMaxAbsorbedOverlapNs = 500'000;

  /// Host time of a sensor time under the clock model as it stands now.
  int64_t ToHost(int64_t sensor_t_ns) const { return clock_.ToHost(sensor_t_ns); }
  const LidarStageCounters& counters() const { return counters_; }
  const drivers::ClockModelStats& clock() const { return clock_.stats(); }
  const drivers::ScanAssemblerStats& assembler() const { return assembler_.stats(); }

 private:
  std::unique_ptr<drivers::LidarPacketDecoder> decoder_;
  drivers::ScanAssembler assembler_;
  drivers::ClockModel clock_;
  drivers::LidarPacketDecoder::ReturnBuffer buffer_{};
  drivers::AssembledScan assembled_;
  LidarStageCounters counters_;
  int64_t last_end_ns_ = 0;  ///< host time of the previous sweep's end
};

}  // namespace swlio::daemon
