#include "swlio/daemon/blackbox/incident_store.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <tuple>

#include "swlio/core/time.h"
#include "swlio/daemon/blackbox/health_row.h"
#include "swlio/daemon/blackbox/recording_concat.h"

namespace swlio::daemon {
namespace {

constexpr char kPartial[] = ".partial";

/// A YAML double-quoted scalar.
std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return out + '"';
}

bool IsPartial(const std::filesystem::path& p) {
  const std::string name = p.filename().string();
  return name.size() > sizeof kPartial - 1 &&
         name.compare(name.size() - (sizeof kPartial - 1), std::string::npos, kPartial) == 0;
}

}  // namespace

IncidentStore::IncidentStore(std::filesystem::path dir,
                             RingSegments* ring,
                             const RecordConfig& config,
                             std::string version)
    : dir_(std::move(dir)), ring_(ring), config_(config), version_(std::move(version)) {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  for (auto it = std::filesystem::directory_iterator(dir_, ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
    if (IsPartial(it->path())) std::filesystem::remove_all(it->path(), ec);  // a crash's
  }
}

void IncidentStore::OnEvent(const IncidentEvent& event) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++counters_.events;
  for (Incident& open : open_) {
    if (event.t_ns <= open.end_ns) {
      open.events.push_back(event);
      return;
    }
  }
  Incident& i = open_.emplace_back();
  i.events.push_back(event);
  i.start_ns = event.t_ns - SecToNs(config_.incident_before_s);
  i.end_ns = event.t_ns + SecToNs(config_.incident_after_s);
}

void IncidentStore::OnSegmentClosed(int64_t end_ns) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = open_.begin(); it != open_.end();) {
    if (it->end_ns <= end_ns) {
      ready_.push_back(std::move(*it));
      it = open_.erase(it);
    } else {
      ++it;
    }
  }
  wake_.notify_one();
}

void IncidentStore::CloseAll() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (Incident& i : open_) {
    i.cut_short = true;
    ready_.push_back(std::move(i));
  }
  open_.clear();
  wake_.notify_one();
}

int64_t IncidentStore::KeepFromNs() const {
  std::lock_guard<std::mutex> lock(mutex_);
  int64_t from = writing_from_ns_;
  for (const Incident& i : open_) from = std::min(from, i.start_ns);
  for (const Incident& i : ready_) from = std::min(from, i.start_ns);
  return from;
}

void IncidentStore::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    beat.Beat();
    wake_.wait_for(lock, std::chrono::milliseconds(100));
    if (ready_.empty()) {
      if (stop.load()) return;
      continue;
    }
    Incident next = std::move(ready_.front());
    ready_.pop_front();
    writing_from_ns_ = next.start_ns;
    lock.unlock();
    Write(next, beat);
    lock.lock();
    writing_from_ns_ = INT64_MAX;
  }
}

std::string IncidentStore::Yaml(const Incident& incident,
                                const std::vector<SegmentInfo>& segments) const {
  const IncidentEvent& first = incident.events.front();
  const int64_t kept_start = segments.empty() ? first.t_ns : segments.front().start_ns;
  const int64_t kept_end = segments.empty() ? first.t_ns : segments.back().end_ns;
  auto utc = [&](int64_t t_ns) { return Quoted(UtcIso(first.realtime_ns + (t_ns - first.t_ns))); };
  std::ostringstream y;
  y << "format: swlio-incident 1\nswlio_version: " << Quoted(version_)
    << "\nreason: " << first.reason << "\nt_event_ns: " << first.t_ns
    << "\nopened_utc: " << Quoted(UtcIso(first.realtime_ns)) << "\n"
    << "# span: what was kept (whole ring segments); asked: incident_before_s / _after_s around\n"
    << "# the first event. Times on the daemon's time base (imu.rx.csv, health.csv t_ns).\n"
    << "span: {start_ns: " << kept_start << ", end_ns: " << kept_end
    << ", start_utc: " << utc(kept_start) << ", end_utc: " << utc(kept_end)
    << ", asked_start_ns: " << incident.start_ns << ", asked_end_ns: " << incident.end_ns
    << ", cut_short: " << (incident.cut_short || kept_end < incident.end_ns ? "true" : "false")
    << ", segments: " << segments.size() << "}\nevents:\n";
  for (const IncidentEvent& e : incident.events) {
    y << "  - {t_ns: " << e.t_ns << ", utc: " << Quoted(UtcIso(e.realtime_ns))
      << ", reason: " << e.reason << ", detail: " << Quoted(e.detail) << "}\n";
  }
  return y.str();
}

void IncidentStore::Write(const Incident& incident, const Watchdog::Handle& beat) {
  const IncidentEvent& first = incident.events.front();
  const std::vector<SegmentInfo> segments = ring_->Overlapping(incident.start_ns, incident.end_ns);
  if (segments.empty()) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.failed;
    counters_.last_error = "incident " + first.reason + ": no ring segment of its span is left";
    spdlog::error("black box: {}", counters_.last_error);
    return;
  }
  std::vector<std::filesystem::path> parts;
  parts.reserve(segments.size());
  for (const SegmentInfo& s : segments) parts.push_back(s.dir);
  WriteParts(parts, UniqueName(first), Yaml(incident, segments), beat);
}

bool IncidentStore::WriteParts(const std::vector<std::filesystem::path>& parts,
                               const std::string& name,
                               const std::string& yaml,
                               const Watchdog::Handle& beat) {
  const std::filesystem::path partial = dir_ / (name + kPartial);
  std::error_code ec;
  std::filesystem::remove_all(partial, ec);
  std::string error;
  bool ok = ConcatenateRecordings(
      parts, partial, [&beat] { beat.Beat(); }, &error);
  if (ok) {
    std::ofstream out(partial / "incident.yaml");
    out << yaml;
    ok = out.flush().good();
    if (!ok) error = "cannot write incident.yaml";
  }
  if (ok) {
    std::filesystem::rename(partial, dir_ / name, ec);
    ok = !ec;
    if (!ok) error = "cannot rename " + partial.string() + ": " + ec.message();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (ok) {
      ++counters_.kept;
      counters_.last_incident = name;
    } else {
      ++counters_.failed;
      counters_.last_error = "incident " + name + ": " + error;
    }
  }
  if (!ok) {
    std::filesystem::remove_all(partial, ec);
    spdlog::error("black box: {}", error);
    return false;
  }
  spdlog::info("black box: incident kept in {} ({} segments, {:.1f} MB)", (dir_ / name).string(),
               parts.size(), static_cast<double>(DirectoryBytes(dir_ / name)) / 1e6);
  Bound();
  return true;
}

void IncidentStore::Bound() {
  struct Kept {
    std::filesystem::file_time_type written;  ///< when it was renamed into place
    std::filesystem::path path;
    uint64_t bytes = 0;
    bool operator<(const Kept& o) const {
      return std::tie(written, path) < std::tie(o.written, o.path);
    }
  };
  std::vector<Kept> kept;
  uint64_t total = 0;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator(dir_, ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
    if (!it->is_directory(ec) || IsPartial(it->path())) continue;
    kept.push_back(
        {std::filesystem::last_write_time(it->path(), ec), it->path(), DirectoryBytes(it->path())});
    total += kept.back().bytes;
  }
  // Oldest first by when each was written (names begin with the UTC time, but a wall clock
  // can step back).
  std::sort(kept.begin(), kept.end());
  const auto max_count = static_cast<size_t>(std::max<int64_t>(config_.incidents_max_count, 1));
  const auto max_bytes = static_cast<uint64_t>(config_.incidents_max_mb) * 1'000'000;
  size_t count = kept.size();
  std::string newest;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    newest = counters_.last_incident;
  }
  for (const auto& [written, path, bytes] : kept) {
    if (count <= max_count && total <= max_bytes) break;
    if (path.filename() == newest) continue;
    std::filesystem::remove_all(path, ec);
    spdlog::info("black box: incident {} removed (incidents_max_count {}, incidents_max_mb {})",
                 path.filename().string(), config_.incidents_max_count, config_.incidents_max_mb);
    --count;
    total -= bytes;
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.removed;
  }
}

std::string IncidentStore::UniqueName(const IncidentEvent& first) const {
  const std::string base = FormatUtc(first.realtime_ns, "%Y%m%dT%H%M%SZ") + "-" + first.reason;
  std::string name = base;
  for (int n = 2; std::filesystem::exists(dir_ / name) && n < 1000; ++n)
    name = base + "-" + std::to_string(n);
  return name;
}

void IncidentStore::KeepLeftovers(const std::vector<std::filesystem::path>& parts,
                                  int64_t realtime_ns) {
  if (parts.empty()) return;
  IncidentEvent e;
  e.realtime_ns = realtime_ns;
  e.reason = "unclean_stop";
  e.detail =
      "the previous run ended without a clean stop (crash, kill, watchdog or power loss): "
      "its last " +
      std::to_string(parts.size()) + " ring segments";
  std::ostringstream y;
  y << "format: swlio-incident 1\nswlio_version: " << Quoted(version_)
    << "\nreason: unclean_stop\nt_event_ns: 0\nopened_utc: " << Quoted(UtcIso(realtime_ns))
    << "\n# The segments of an earlier run: times on that run's clock (see health.csv).\n"
    << "span: {segments: " << parts.size() << ", cut_short: true}\nevents:\n"
    << "  - {t_ns: 0, utc: " << Quoted(UtcIso(realtime_ns))
    << ", reason: unclean_stop, detail: " << Quoted(e.detail) << "}\n";
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counters_.events;
  }
  WriteParts(parts, UniqueName(e), y.str(), Watchdog::Handle{});
}

IncidentCounters IncidentStore::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  IncidentCounters c = counters_;
  c.pending = open_.size() + ready_.size() + (writing_from_ns_ != INT64_MAX ? 1 : 0);
  return c;
}

}  // namespace swlio::daemon
