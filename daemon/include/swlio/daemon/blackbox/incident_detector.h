#pragma once
/// @file
/// Turns the daemon's health, looked at about once a second, into incident events: the moments
/// a field engineer will ask about (docs/blackbox.md). Edges, not levels: a LiDAR that stays
/// silent makes one event when it falls silent, another only after it streamed again. An event
/// of one reason repeats at most every kRepeatNs.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "swlio/daemon/blackbox/incident_event.h"
#include "swlio/daemon/runtime/health.h"

namespace swlio::daemon {

class IncidentDetector {
 public:
  static constexpr int64_t kSilentNs = 1'000'000'000;      ///< a sensor silent this long
  static constexpr int64_t kRepeatNs = 10'000'000'000;     ///< one reason at most this often
  static constexpr int64_t kAmbiguousNs = 30'000'000'000;  ///< confirming this long
  /// LiDAR packets missing or bad in one look, at least this many and this fraction.
  static constexpr uint64_t kLossyMinPackets = 10;
  static constexpr double kLossyFraction = 0.01;

  /// The events since the previous call. `stalled`: the watchdog's stalled threads (empty:
  /// every thread progresses).
  std::vector<IncidentEvent> Update(const HealthSnapshot& s,
                                    int64_t t_ns,
                                    int64_t realtime_ns,
                                    const std::vector<std::string>& stalled = {});

 private:
  struct Silence {
    uint64_t last_count = 0;
    int64_t last_change_ns = 0;
    bool seen = false;    ///< the sensor has streamed
    bool silent = false;  ///< an event was made for this silence
  };
  void Emit(const std::string& reason, std::string detail);
  void CheckSilence(Silence* s, uint64_t count, const char* reason, const char* sensor);
  void CheckSensors(const HealthSnapshot& now, const HealthSnapshot& before);
  void CheckEstimator(const HealthSnapshot& now, const HealthSnapshot& before);
  void CheckLocalization(const HealthSnapshot& now, const HealthSnapshot& before);

  HealthSnapshot previous_;
  bool have_previous_ = false;
  Silence lidar_, imu_;
  int64_t confirming_since_ns_ = -1;
  bool ambiguous_ = false;
  bool watchdog_stalled_ = false;
  std::map<std::string, int64_t> last_emitted_ns_;
  std::vector<IncidentEvent> out_;
  int64_t t_ns_ = 0;
  int64_t realtime_ns_ = 0;
};

/// Queue drops of the pipeline (not the recorder's own queues: a slow disk is the black box's
/// trouble, reported in its health, not an incident of localization).
uint64_t PipelineDrops(const HealthSnapshot& s);

}  // namespace swlio::daemon
