#include "swlio/daemon/state/time_offset_keeper.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>

#include "swlio/daemon/blackbox/health_row.h"
#include "swlio/daemon/output/stamp_clock.h"

namespace swlio::daemon {
namespace {

constexpr double kMinMoveS = 2e-5;  // 0.02 ms: below any use of the offset

}  // namespace

TimeOffsetKeeper::TimeOffsetKeeper(std::string path, int64_t period_ns)
    : path_(std::move(path)), period_ns_(period_ns) {}

void TimeOffsetKeeper::Apply(estimator::TimeOffsetConfig* config) {
  if (path_.empty()) return;
  const double start_ms = config->initial_offset_s * 1e3;
  if (!config->enabled || !config->estimate) {
    spdlog::info("time offset: not estimated online (fixed at {:.2f} ms); {} is not used",
                 config->enabled ? start_ms : 0.0, path_);
    path_.clear();
    return;
  }
  std::error_code ec;
  if (!std::filesystem::exists(path_, ec)) {
    spdlog::info("time offset: no saved estimate in {} yet; starting from {:.2f} ms", path_,
                 start_ms);
    return;
  }
  std::string error;
  saved_ = ReadTimeOffsetState(path_, &error);
  if (!saved_) {
    spdlog::warn("time offset: {}; starting from {:.2f} ms (the file is replaced once estimated)",
                 error, start_ms);
    return;
  }
  if (std::abs(saved_->offset_s) > config->max_offset_s) {
    spdlog::warn(
        "time offset: {} holds {:.2f} ms, beyond estimator.window.time_offset.max_offset_s "
        "({:.2f} ms); starting from {:.2f} ms",
        path_, saved_->offset_s * 1e3, config->max_offset_s * 1e3, start_ms);
    return;
  }
  config->initial_offset_s = saved_->offset_s;
  spdlog::info("time offset: starting from {:.3f} ms (σ {:.3f} ms, saved {}) in {}",
               saved_->offset_s * 1e3, saved_->sigma_s * 1e3, saved_->saved_utc, path_);
}

bool TimeOffsetKeeper::IsNews(const estimator::TimeOffsetStatus& status) const {
  if (path_.empty() || !status.enabled || !status.gated || status.updates == 0) return false;
  if (!std::isfinite(status.estimate_s) || !(status.sigma_s > 0.0)) return false;
  if (!saved_) return true;
  // Narrower, or apart by more than both uncertainties allow (a sensor or adapter changed):
  // a fresh start's first, wider estimate near the kept one does not replace it.
  const double moved_s = std::abs(status.estimate_s - saved_->offset_s);
  const double apart_s = std::max(kMinMoveS, 3.0 * std::hypot(status.sigma_s, saved_->sigma_s));
  return status.sigma_s < 0.8 * saved_->sigma_s || moved_s > apart_s;
}

void TimeOffsetKeeper::Observe(const estimator::TimeOffsetStatus& status, int64_t now_ns) {
  if (!IsNews(status)) return;
  if (last_write_ns_ && now_ns - *last_write_ns_ < period_ns_) return;
  last_write_ns_ = now_ns;
  Save(status);
}

void TimeOffsetKeeper::Flush(const estimator::TimeOffsetStatus& status) {
  if (IsNews(status)) Save(status);
}

void TimeOffsetKeeper::Save(const estimator::TimeOffsetStatus& status) {
  SavedTimeOffset s;
  s.offset_s = status.estimate_s;
  s.sigma_s = status.sigma_s;
  s.updates = status.updates;
  s.saved_utc = FormatUtc(RealtimeNowNs(), "%Y-%m-%dT%H:%M:%SZ");
  std::string error;
  if (!WriteTimeOffsetState(path_, s, &error)) {
    if (error != last_error_) spdlog::warn("time offset: not saved: {}", error);
    last_error_ = error;
    return;
  }
  last_error_.clear();
  ++writes_;
  spdlog::info("time offset: {:.3f} ms (σ {:.3f} ms) saved to {}", s.offset_s * 1e3,
               s.sigma_s * 1e3, path_);
  saved_ = std::move(s);
}

}  // namespace swlio::daemon
