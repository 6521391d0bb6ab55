#pragma once
/// @file
/// Builds sweeps (swlio::Scan) from the decoded packets of any LidarPacketDecoder.
///
/// Cut: a sweep ends where the azimuth, going round, crosses `cut_angle_deg`.
/// Gaps: between consecutive packets the sensor time and the first-block azimuth must advance
/// by about one packet. A larger advance is a gap; the missing packets are counted (from the
/// time step, or from the azimuth step when that says more) and charged to the sweep in
/// progress, which is then flagged partial. A time that goes backwards or jumps by half a
/// revolution or more is a discontinuity: the sweep in progress is closed (partial) and a new
/// one starts, so sweeps are never merged across it. The first sweep of a stream (it did not
/// start at the cut) and the one closed by Flush() (it did not end at the cut) are partial too.
/// The cut tracks the azimuth unwrapped from sample to sample (returns and each packet's first
/// block), so per-laser horizontal offsets that jitter around the cut cannot split a sweep twice.
///
/// Clock: `Scan::t_start_ns`, `t_end_ns` and each point's `dt_ns` come from
/// `LidarReturn::t_sensor_ns`, i.e. the SENSOR clock (RS16 header time), not host time; the
/// clock model maps them later. The host receive times given to AddPacket travel alongside.
///
/// No allocation in steady state: PopScan() swaps storage with the caller's AssembledScan, so a
/// caller that reuses one AssembledScan recycles its point buffer.

#include <array>
#include <cstdint>
#include <span>

#include "swlio/core/types.h"
#include "swlio/drivers/lidar_decoder.h"

namespace swlio::drivers {

struct ScanAssemblerConfig {
  double cut_angle_deg = 0.0;            ///< [0, 360)
  double packets_per_revolution = 75.0;  ///< from LidarPacketDecoder::PacketsPerRevolution()
  /// 60e9 / rpm; 0 when unknown: then only backward time steps are checked, gaps come from
  /// the azimuth alone.
  int64_t revolution_period_ns = 100'000'000;
  /// A step larger than this many nominal packet steps is a gap.
  double gap_tolerance_packets = 1.5;
  /// Points reserved per sweep at start-up (RS16 single return: 16 × ~1800 firings).
  size_t reserve_points = 32'000;
};

/// A completed sweep plus what the assembler knows about it.
struct AssembledScan {
  Scan scan;  ///< times on the sensor clock (see file comment); `partial` set as described
  int64_t host_rx_first_ns = 0;  ///< host receive time of the sweep's first packet (0 if unknown)
  int64_t host_rx_last_ns = 0;   ///< host receive time of its last packet
  uint32_t packets = 0;          ///< data packets that contributed returns or slots
  uint32_t missing_packets = 0;  ///< packets detected missing inside or just before the sweep
  bool started_at_cut = false;   ///< begun by crossing the cut angle (not by a gap / stream start)
  bool ended_at_cut = false;     ///< ended by crossing the cut angle (not by a gap / Flush)
  float first_azimuth_deg = 0.0f;
  float last_azimuth_deg = 0.0f;
};

struct ScanAssemblerStats {
  uint64_t packets = 0;
  uint64_t scans = 0;
  uint64_t partial_scans = 0;
  uint64_t gaps = 0;             ///< gap events
  uint64_t missing_packets = 0;  ///< packets estimated missing, summed over all gaps
  uint64_t discontinuities = 0;  ///< time went backwards or jumped by half a revolution or more
  uint64_t dropped_scans = 0;    ///< completed sweeps overwritten because PopScan() lagged
};

class ScanAssembler {
 public:
  explicit ScanAssembler(const ScanAssemblerConfig& config);

  /// Updates the nominal packet rate, e.g. after a DIFOP changed rpm or return mode.
  void SetNominal(double packets_per_revolution, int64_t revolution_period_ns);

  /// Adds one decoded data packet (`returns` as DecodeData wrote them, in firing order).
  /// Returns the number of completed sweeps now waiting in PopScan() (at most 2).
  int AddPacket(std::span<const LidarReturn> returns,
                const LidarPacketSummary& summary,
                int64_t host_rx_ns = 0);

  /// Closes the sweep in progress (partial: it did not end at the cut), if it has points.
  int Flush();

  /// Moves the oldest completed sweep into `out` (swapping storage). False when none waits.
  bool PopScan(AssembledScan* out);

  const ScanAssemblerStats& stats() const { return stats_; }

 private:
  static constexpr int kMaxReady = 3;
  /// Detects a gap/discontinuity before `summary`'s packet; closes the sweep when found.
  void CheckContinuity(const LidarPacketSummary& summary);
  /// Advances the unwrapped azimuth; closes the sweep and starts the next at a cut crossing.
  void Advance(float azimuth_deg);
  void AddReturn(const LidarReturn& r);
  void CloseCurrent(bool ended_at_cut);
  void StartNew(bool at_cut, double relative_azimuth_deg);
  double RelativeAzimuth(float azimuth_deg) const;

  ScanAssemblerConfig config_;
  ScanAssemblerStats stats_;
  AssembledScan current_;
  bool current_open_ = false;
  double previous_relative_deg_ = 0.0;  ///< relative azimuth of the last sample
  double unwrapped_deg_ = 0.0;          ///< relative azimuth accumulated since the sweep began
  uint32_t pending_missing_ = 0;        ///< missing packets to charge to the next sweep
  uint64_t packet_id_ = 0;              ///< id of the packet being added
  uint64_t current_last_packet_id_ = 0;
  bool have_previous_ = false;
  int64_t previous_t_ns_ = 0;
  float previous_first_azimuth_deg_ = 0.0f;
  int64_t current_host_rx_ns_ = 0;
  uint64_t next_seq_ = 0;
  std::array<AssembledScan, kMaxReady> ready_{};
  int ready_head_ = 0;
  int ready_count_ = 0;
};

}  // namespace swlio::drivers
