#pragma once
/// @file
/// The file that keeps the LiDAR–IMU time offset swliod estimated online across restarts
/// (YAML `state.time_offset_file`; time_offset_keeper.h says when it is read and written):
///
///   format: swlio-time-offset 1
///   offset_s: -0.0103412   # the estimate that last passed its gate (time_offset_estimator.h)
///   sigma_s: 8.62e-05      # its standard deviation
///   updates: 1843          # sweeps at which the gate had passed by then
///   saved_utc: 2026-12-06T07:12:30Z
///
/// Written whole to `<file>.tmp`, flushed, then renamed over the file: a power cut leaves the
/// old file or the new one, never half of one. Reading rejects anything else with a reason.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace swlio::daemon {

/// An offset beyond this is no sensor's delay (TimeOffsetConfig::max_offset_s allows 0.2 s).
inline constexpr double kMaxSavedTimeOffsetS = 0.2;

struct SavedTimeOffset {
  double offset_s = 0.0;  ///< the convention of time_offset_estimator.h (> 0: IMU stamps late)
  double sigma_s = 0.0;   ///< 1 ns … 0.2 s
  uint64_t updates = 0;   ///< ≥ 1: only a gated estimate is kept
  /// ISO 8601 (letters, digits, ":+-.", ≤ 40), for the operator; not interpreted.
  std::string saved_utc;
};

/// The file's text (what WriteTimeOffsetState writes).
std::string FormatTimeOffsetState(const SavedTimeOffset& saved);
/// The values in `text`, or nothing with `*error` saying which key is wrong and why.
std::optional<SavedTimeOffset> ParseTimeOffsetState(const std::string& text, std::string* error);
/// The file at `path`; nothing with `*error` (cannot open, too large, or ParseTimeOffsetState's
/// reason), prefixed by the path.
std::optional<SavedTimeOffset> ReadTimeOffsetState(const std::filesystem::path& path,
                                                   std::string* error);
/// Replaces the file at `path` (through `<path>.tmp` and rename); false with `*error`.
bool WriteTimeOffsetState(const std::filesystem::path& path,
                          const SavedTimeOffset& saved,
                          std::string* error);

}  // namespace swlio::daemon
