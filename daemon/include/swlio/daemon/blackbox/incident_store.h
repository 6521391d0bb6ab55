#pragma once
/// @file
/// Incidents: an event opens one spanning [event − incident_before_s, event + incident_after_s];
/// events inside an open span join it. Once the ring has closed a segment past the span's end
/// (or the recording ends), the keeper thread joins the span's segments into
/// incidents/<UTC>-<reason>/ (recording_concat.h) with incident.yaml, then removes the oldest
/// incidents beyond incidents_max_count / incidents_max_mb, never the newest. Folders appear
/// complete (written as .partial, then renamed). Layout: docs/blackbox.md.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "swlio/daemon/blackbox/incident_event.h"
#include "swlio/daemon/blackbox/ring_segments.h"
#include "swlio/daemon/config/daemon_config.h"
#include "swlio/daemon/runtime/watchdog.h"

namespace swlio::daemon {

struct IncidentCounters {
  uint64_t events = 0;
  uint64_t kept = 0;          ///< incidents written
  uint64_t failed = 0;        ///< incidents that could not be written (see last_error)
  uint64_t removed = 0;       ///< by the count and size bounds
  uint64_t pending = 0;       ///< open, or waiting for the keeper
  std::string last_incident;  ///< folder name of the newest
  std::string last_error;
};

class IncidentStore {
 public:
  /// `dir`: the incidents folder (created when needed). `version`: written in incident.yaml.
  IncidentStore(std::filesystem::path dir,
                RingSegments* ring,
                const RecordConfig& config,
                std::string version);

  /// Recorder thread: an event (opens an incident or joins the open one).
  void OnEvent(const IncidentEvent& event);
  /// Recorder thread: the ring closed a segment ending at `end_ns`; incidents whose span ended
  /// by then go to the keeper.
  void OnSegmentClosed(int64_t end_ns);
  /// Recorder thread: no segment will come any more; every open incident goes as it is.
  void CloseAll();
  /// The oldest moment an open or unwritten incident still needs (INT64_MAX: none).
  int64_t KeepFromNs() const;
  /// Keeper thread: writes incidents until `stop` is set and nothing is left to write.
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  /// Writes `parts` (folders of an earlier run that did not stop cleanly) as one incident, now
  /// (before the threads start).
  void KeepLeftovers(const std::vector<std::filesystem::path>& parts, int64_t realtime_ns);

  IncidentCounters counters() const;

 private:
  struct Incident {
    std::vector<IncidentEvent> events;
    int64_t start_ns = 0;  ///< the span asked for
    int64_t end_ns = 0;
    bool cut_short = false;  ///< the recording ended before end_ns
  };
  void Write(const Incident& incident, const Watchdog::Handle& beat);
  /// incident.yaml for `incident` kept as `segments`.
  std::string Yaml(const Incident& incident, const std::vector<SegmentInfo>& segments) const;
  bool WriteParts(const std::vector<std::filesystem::path>& parts,
                  const std::string& name,
                  const std::string& yaml,
                  const Watchdog::Handle& beat);
  void Bound();
  std::string UniqueName(const IncidentEvent& first) const;

  std::filesystem::path dir_;
  RingSegments* ring_;
  RecordConfig config_;
  std::string version_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Incident> open_;
  std::deque<Incident> ready_;
  int64_t writing_from_ns_ = INT64_MAX;  ///< span start of the incident being written
  IncidentCounters counters_;
};

}  // namespace swlio::daemon
