#pragma once
/// @file
/// What swliod keeps of its LiDAR–IMU time offset across restarts (time_offset_state.h holds
/// the file). Until the motion first reveals the offset (the first sharp turn: 9 s into
/// `aggressive`), the estimator integrates the IMU at the offset it started from; started
/// 5–10 ms off, the APE of that drive came out 15–23 % above the run with the offset known,
/// started at the offset found it came out at or below it (bench/README, "The field"). So a
/// start begins where the last run's estimate ended.
///
/// - Start (Apply): where the offset is estimated online, the saved estimate replaces
///   `initial_offset_s`. A calibration given as fixed (`estimate: false`) wins over the file;
///   a saved offset beyond `max_offset_s` or a malformed file is logged and left alone.
/// - Running (Observe, about every second): a gated estimate is written, at most every
///   `period_ns`, when its σ is a fifth narrower than the kept one's, or when the two lie over
///   3 σ apart (their σ combined; a sensor or adapter changed). A fresh start's first estimate,
///   wider and near the kept one, leaves the file alone.
/// - Stop (Flush): the same, without the period.
/// A write that fails is logged once per kind of failure; the daemon runs on either way.

#include <cstdint>
#include <optional>
#include <string>

#include "swlio/daemon/state/time_offset_state.h"
#include "swlio/estimator/window/time_offset_estimator.h"

namespace swlio::daemon {

class TimeOffsetKeeper {
 public:
  /// `path` empty: nothing is read or written.
  TimeOffsetKeeper(std::string path, int64_t period_ns);

  /// The start from the file, into `config`; the log line says what was done and why.
  void Apply(estimator::TimeOffsetConfig* config);
  /// The estimator's status now (host time `now_ns`): written when it says something new.
  void Observe(const estimator::TimeOffsetStatus& status, int64_t now_ns);
  /// At stop: the last word, whatever the period.
  void Flush(const estimator::TimeOffsetStatus& status);

  /// What the file holds as far as this keeper knows (read at Apply, or written since).
  const std::optional<SavedTimeOffset>& saved() const { return saved_; }
  uint64_t writes() const { return writes_; }

 private:
  bool IsNews(const estimator::TimeOffsetStatus& status) const;
  void Save(const estimator::TimeOffsetStatus& status);

  std::string path_;
  int64_t period_ns_;
  std::optional<int64_t> last_write_ns_;
  std::optional<SavedTimeOffset> saved_;
  std::string last_error_;
  uint64_t writes_ = 0;
};

}  // namespace swlio::daemon
