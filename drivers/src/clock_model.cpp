#include "swlio/drivers/clock_model.h"

#include <algorithm>
#include <cmath>

namespace swlio::drivers {

ClockModel::ClockModel(const ClockModelConfig& config) : config_(config) {}

int64_t ClockModel::UnwrapConst(int64_t sensor_t_ns) const {
  if (config_.wrap_period_ns <= 0) return sensor_t_ns;
  int64_t t = sensor_t_ns + wrap_offset_;
  // A query just before the latest wrap (or just after the next one) stays continuous.
  const int64_t last = last_raw_ + wrap_offset_;
  if (t - last > config_.wrap_period_ns / 2) t -= config_.wrap_period_ns;
  if (last - t > config_.wrap_period_ns / 2) t += config_.wrap_period_ns;
  return t;
}

int64_t ClockModel::Unwrap(int64_t sensor_t_ns) {
  if (config_.wrap_period_ns > 0 && have_last_raw_ &&
      last_raw_ - sensor_t_ns > config_.wrap_period_ns / 2) {
    wrap_offset_ += config_.wrap_period_ns;
    ++stats_.wraps;
  }
  have_last_raw_ = true;
  last_raw_ = sensor_t_ns;
  return sensor_t_ns + wrap_offset_;
}

void ClockModel::Restart(int64_t sensor_unwrapped, int64_t host_rx_ns) {
  ref_sensor_ = sensor_unwrapped;
  ref_host_ = host_rx_ns;
  windows_.clear();
  c0_ = 0.0;
  c1_ = 0.0;
  jump_run_ = 0;
  jump_sign_ = 0;
}

void ClockModel::AddToEnvelope(double x, double d) {
  const double window = static_cast<double>(config_.window_ns);
  if (windows_.empty() || x >= windows_.back().start + window) {
    windows_.push_back({x, x, d});
    while (static_cast<int>(windows_.size()) > config_.max_windows) windows_.pop_front();
  } else if (d < windows_.back().d) {
    windows_.back().d = d;
    windows_.back().x = x;
  }
}

// The line under every window minimum that is closest to them in sum (Moon, Skelly, Towsley,
// "Estimation and removal of clock skew from network delay measurements", INFOCOM 1999: the
// linear-programming skew estimate). Its optimum is the lower convex hull's edge that spans
// the minima's mean x. Unlike a least-squares line, a window whose every sample was delayed
// (a loaded host: its minimum lies high) cannot tilt it; only low points, which delays never
// make, shape it.
double ClockModel::HullSlope(size_t count) const {
  std::vector<const WindowMin*>& hull = hull_;
  hull.clear();
  double mean_x = 0.0;
  for (size_t i = 0; i < count; ++i) {
    const WindowMin* p = &windows_[i];
    mean_x += p->x;
    // Windows are in x order: Andrew's monotone chain, lower half.
    while (hull.size() >= 2) {
      const WindowMin& a = *hull[hull.size() - 2];
      const WindowMin& b = *hull.back();
      if ((b.x - a.x) * (p->d - a.d) - (b.d - a.d) * (p->x - a.x) > 0.0) break;  // left turn
      hull.pop_back();
    }
    hull.push_back(p);
  }
  mean_x /= static_cast<double>(count);
  for (size_t i = 1; i < hull.size(); ++i) {
    if (hull[i]->x >= mean_x || i + 1 == hull.size()) {
      const double dx = hull[i]->x - hull[i - 1]->x;
      return dx > 0.0 ? (hull[i]->d - hull[i - 1]->d) / dx : 0.0;
    }
  }
  return 0.0;
}

void ClockModel::Fit() {
  // The newest window is still filling: its minimum is not yet representative, so the slope
  // comes from completed windows only (at least 4, else no drift), and every window, the
  // newest included, then lowers the line onto the envelope.
  const size_t completed = windows_.size() - 1;
  c0_ = 0.0;
  if (completed >= 4) {
    const double slope = HullSlope(completed);
    if (std::abs(slope) * 1e6 <= config_.max_drift_ppm) c1_ = slope;
  } else {
    c1_ = 0.0;
  }
  double lowest = windows_.front().d - Predict(windows_.front().x);
  for (const WindowMin& w : windows_) lowest = std::min(lowest, w.d - Predict(w.x));
  c0_ += lowest;
}

int64_t ClockModel::Observe(int64_t sensor_t_ns, int64_t host_rx_ns) {
  const int64_t s = Unwrap(sensor_t_ns);
  ++stats_.samples;
  if (!stats_.valid) {
    Restart(s, host_rx_ns);
    stats_.valid = true;
  }
  double x = static_cast<double>(s - ref_sensor_);
  double d = static_cast<double>(host_rx_ns - ref_host_) - x;
  if (!windows_.empty()) {
    const double residual = d - Predict(x);
    const int sign = residual > 0 ? 1 : -1;
    // In the first window the model rests on its first sample, which may itself have been late
    // (a loaded host at start): earlier arrivals then only lower the envelope.
    const bool young = windows_.size() == 1 && sign < 0;
    if (!young && std::abs(residual) > static_cast<double>(config_.jump_threshold_ns)) {
      jump_run_ = (sign == jump_sign_) ? jump_run_ + 1 : 1;
      jump_sign_ = sign;
      if (jump_run_ == 1) {
        jump_run_start_x_ = x;
        jump_run_min_residual_ = residual;
      }
      jump_run_min_residual_ = std::min(jump_run_min_residual_, residual);
      const bool lasted = sign < 0 || x - jump_run_start_x_ >= LateConfirmNs();
      if (jump_run_ < config_.jump_confirm_samples || !lasted) {
        ++stats_.rejected;
        return ToHost(sensor_t_ns);
      }
      ++stats_.jumps;
      Restart(s, host_rx_ns);
      x = 0.0;
      d = 0.0;
    }
    jump_run_ = 0;
  }
  AddToEnvelope(x, d);
  Fit();
  stats_.offset_ns = static_cast<double>(ref_host_ - ref_sensor_) + Predict(x) -
                     static_cast<double>(config_.fixed_latency_ns);
  stats_.drift_ppm = c1_ * 1e6;
  return ToHost(sensor_t_ns);
}

double ClockModel::LateConfirmNs() const {
  const bool backlog =
      config_.backlog_ns > 0 && jump_run_min_residual_ <= static_cast<double>(config_.backlog_ns);
  return static_cast<double>(backlog ? std::max(config_.late_jump_confirm_ns, config_.backlog_ns)
                                     : config_.late_jump_confirm_ns);
}

int64_t ClockModel::ToHost(int64_t sensor_t_ns) const {
  const int64_t s = UnwrapConst(sensor_t_ns);
  const double x = static_cast<double>(s - ref_sensor_);
  return ref_host_ + (s - ref_sensor_) + static_cast<int64_t>(std::llround(Predict(x))) -
         config_.fixed_latency_ns;
}

}  // namespace swlio::drivers
