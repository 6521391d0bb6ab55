#pragma once
/// @file
/// Maps one sensor's own clock to host time (CLOCK_MONOTONIC ns) from (sensor time, host
/// receive time) pairs — the one place where sensor time becomes host time.
///
/// Model: host = sensor + offset(sensor), offset linear in sensor time (offset + drift). Every
/// observation satisfies host_rx = true_host + delay with delay ≥ fixed latency, and USB-serial
/// bursts or network queues only ever add delay, so the lower envelope of (host_rx − sensor) is
/// the clock relation. The envelope is kept as the minimum per window (default 1 s of sensor
/// time); the drift is the slope of the line under the recent window minima that lies closest
/// to them (their lower convex hull), the line is lowered onto the minima, and the fixed
/// latency is subtracted.
///
/// Wraps (e.g. Xsens SampleTimeFine every 2³² × 100 µs) are unwrapped with the configured
/// period. A jump (GPS time arriving, a device reset) shows as residuals beyond a threshold in
/// the same direction for several consecutive samples: the model restarts and counts it.
/// Pure: time is passed in; no system clock is read here.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

namespace swlio::drivers {

struct ClockModelConfig {
  int64_t window_ns = 1'000'000'000;        ///< envelope window, sensor time
  int max_windows = 30;                     ///< windows kept for the drift fit
  int64_t wrap_period_ns = 0;               ///< sensor clock period (0: does not wrap)
  int64_t fixed_latency_ns = 0;             ///< known minimum delay (transmission time, …)
  int64_t jump_threshold_ns = 200'000'000;  ///< |residual| beyond this is a jump candidate
  int jump_confirm_samples = 5;             ///< consecutive candidates that confirm a jump
  /// Samples arriving earlier than the model allows can only mean the sensor clock jumped
  /// ahead; arriving later can also be a backlog (a stalled sender or reader on a loaded host,
  /// hundreds of ms). A jump to later is therefore confirmed only once its candidates have
  /// lasted this long in sensor time; until then they are mapped by the model as it stands.
  int64_t late_jump_confirm_ns = 1'000'000'000;
  /// How late a backlog can make a sample (what the buffers between sensor and reader hold, in
  /// time); 0: no allowance. Candidates at most this late are a jump only once they have lasted
  /// `backlog_ns` too: a reader starved for seconds on a busy host is not a clock that stepped
  /// back, while a step back by more than any buffer holds is still confirmed quickly.
  int64_t backlog_ns = 0;
  /// A fitted drift beyond this is not a clock's (crystals: tens of ppm) but late arrivals
  /// filling the first windows after a start (a loaded host); the previous drift is kept.
  double max_drift_ppm = 1000.0;
};

struct ClockModelStats {
  uint64_t samples = 0;
  uint64_t jumps = 0;      ///< confirmed jumps (model restarted)
  uint64_t wraps = 0;      ///< sensor clock wraps unwrapped
  uint64_t rejected = 0;   ///< samples ignored as jump candidates
  double offset_ns = 0.0;  ///< host − sensor at the latest sample (latency removed)
  double drift_ppm = 0.0;  ///< d(offset)/d(sensor time) × 1e6
  bool valid = false;      ///< at least one sample since the last restart
};

class ClockModel {
 public:
  explicit ClockModel(const ClockModelConfig& config = {});

  /// Adds an observation; returns the host time of `sensor_t_ns` under the updated model.
  int64_t Observe(int64_t sensor_t_ns, int64_t host_rx_ns);

  /// Host time of a sensor time (unwrapped against the latest observation). Only meaningful
  /// once `stats().valid`.
  int64_t ToHost(int64_t sensor_t_ns) const;

  const ClockModelStats& stats() const { return stats_; }

 private:
  struct WindowMin {
    double start = 0.0;  ///< where the window begins (sensor time − reference, ns)
    double x = 0.0;      ///< where its minimum is
    double d = 0.0;      ///< minimum of (host − reference) − x in the window
  };

  int64_t Unwrap(int64_t sensor_t_ns);
  int64_t UnwrapConst(int64_t sensor_t_ns) const;
  void Restart(int64_t sensor_unwrapped, int64_t host_rx_ns);
  void AddToEnvelope(double x, double d);
  void Fit();
  /// How long a run of late candidates must last to be a jump (sensor ns).
  double LateConfirmNs() const;
  /// Drift from the first `count` windows (see clock_model.cpp).
  double HullSlope(size_t count) const;
  double Predict(double x) const { return c0_ + c1_ * x; }

  ClockModelConfig config_;
  ClockModelStats stats_;
  int64_t ref_sensor_ = 0;
  int64_t ref_host_ = 0;
  bool have_last_raw_ = false;
  int64_t last_raw_ = 0;
  int64_t wrap_offset_ = 0;
  std::deque<WindowMin> windows_;
  double c0_ = 0.0;
  double c1_ = 0.0;
  mutable std::vector<const WindowMin*> hull_;  ///< HullSlope's scratch (no allocation per call)
  int jump_run_ = 0;
  int jump_sign_ = 0;
  double jump_run_start_x_ = 0.0;       ///< sensor time (x) of the run's first candidate
  double jump_run_min_residual_ = 0.0;  ///< the run's least late candidate (ns)
};

}  // namespace swlio::drivers
