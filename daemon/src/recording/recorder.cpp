#include "swlio/daemon/recording/recorder.h"

#include <spdlog/spdlog.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "swlio/core/time.h"
#include "swlio/daemon/config/config_printer.h"
#include "swlio/daemon/runtime/version.h"

namespace swlio::daemon {

RecordingSetup MakeRecordingSetup(const DaemonConfig& config,
                                  const Eigen::Isometry3d& T_imu_lidar,
                                  const TimeScale& time) {
  RecordingSetup s;
  s.config = &config;
  s.T_imu_lidar = T_imu_lidar;
  s.time = time;
  s.config_text = PrintConfig(config);
  s.version = SwlioVersion();
  s.msop_port = static_cast<uint16_t>(config.lidar.msop_port);
  s.difop_port = static_cast<uint16_t>(config.lidar.difop_port);
  return s;
}

Recorder::Recorder(const RecordingSetup& setup, const StampClock* stamps) : setup_(setup) {
  if (stamps != nullptr) clocks_ = stamps->clocks();
}

Recorder::~Recorder() = default;

bool Recorder::OpenFolder(const std::filesystem::path& dir, std::string* error) {
  const ClockOffsetSample start = SampleClockOffset(clocks_);
  files_ = RecordingFiles::Open(dir, setup_, start, error);
  if (!files_) return false;
  last_offset_row_ns_ = start.offset_ns;
  segment_start_ns_ = setup_.time.ToDaemon(MonotonicNowNs());
  return true;
}

std::unique_ptr<Recorder> Recorder::Create(const std::filesystem::path& dir,
                                           const DaemonConfig& config,
                                           const Eigen::Isometry3d& T_imu_lidar,
                                           const TimeScale& time,
                                           std::string* error,
                                           const StampClock* stamps) {
  // The setup points at the configuration: keep a copy that lives as long as the recorder.
  auto owned = std::make_shared<DaemonConfig>(config);
  std::unique_ptr<Recorder> r(new Recorder(MakeRecordingSetup(*owned, T_imu_lidar, time), stamps));
  r->owned_config_ = std::move(owned);
  if (!r->OpenFolder(dir, error)) return nullptr;
  return r;
}

std::unique_ptr<Recorder> Recorder::CreateRing(const RecordingSetup& setup,
                                               std::string* error,
                                               const StampClock* stamps) {
  const RecordConfig& c = setup.config->record;
  std::unique_ptr<Recorder> r(new Recorder(setup, stamps));
  r->ring_dir_ = std::filesystem::path(c.directory) / "ring";
  std::error_code ec;
  std::filesystem::create_directories(r->ring_dir_, ec);
  if (ec) {
    *error = "black box: cannot create " + r->ring_dir_.string() + ": " + ec.message();
    return nullptr;
  }
  r->ring_ = std::make_unique<RingSegments>(r->ring_dir_);
  r->store_ = std::make_unique<IncidentStore>(std::filesystem::path(c.directory) / "incidents",
                                              r->ring_.get(), c, setup.version);
  const std::vector<std::filesystem::path> leftovers = r->ring_->Leftovers();
  const std::filesystem::path mark = r->ring_dir_ / kCleanStopMark;
  if (!leftovers.empty() && !std::filesystem::exists(mark, ec)) {
    spdlog::warn("black box: the previous run did not stop cleanly; keeping its last {} segments",
                 leftovers.size());
    r->store_->KeepLeftovers(leftovers, SampleClockOffset(r->clocks_).offset_ns + MonotonicNowNs());
  }
  const std::filesystem::path first = r->ring_->NextDir();  // numbers go on after leftovers
  for (const std::filesystem::path& p : leftovers) std::filesystem::remove_all(p, ec);
  std::filesystem::remove(mark, ec);
  if (!r->OpenFolder(first, error)) {
    *error = "black box: " + *error;
    return nullptr;
  }
  return r;
}

void Recorder::AddHealthRow(std::string row) {
  std::lock_guard<std::mutex> lock(side_mutex_);
  if (health_rows_.size() < 600) health_rows_.push_back(std::move(row));
}

void Recorder::AddEvent(IncidentEvent event) {
  if (!store_) return;
  std::lock_guard<std::mutex> lock(side_mutex_);
  events_.push_back(std::move(event));
}

void Recorder::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  int64_t next_housekeeping_ns = MonotonicNowNs() + 1'000'000'000;
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    LidarPacket p;
    if (!Drain() && lidar_.WaitPop(&p, 50'000)) WritePacket(p);  // sleep until data arrives
    const int64_t now = MonotonicNowNs();
    RecordClockOffset(now);
    BoundRing(now);
    if (now >= next_housekeeping_ns) {
      Housekeep();
      next_housekeeping_ns = now + 1'000'000'000;
    }
  }
  while (Drain()) {
  }
  next_offset_check_ns_ = 0;  // the offset as the recording ends
  RecordClockOffset(MonotonicNowNs());
  Finish();
}

void Recorder::WritePacket(const LidarPacket& p) {
  if (!files_) return discarded_.fetch_add(1, std::memory_order_relaxed), void();
  files_->Packet(setup_.time.ToDaemon(p.t_rx_ns), p.difop, std::span(p.bytes).first(p.size));
  lidar_packets_.fetch_add(1, std::memory_order_relaxed);
}

bool Recorder::Drain() {
  bool any = false;
  LidarPacket p;
  while (lidar_.Pop(&p)) {
    WritePacket(p);
    any = true;
  }
  drivers::CanRxFrame f;
  while (can_.Pop(&f)) {
    if (files_) files_->Can(setup_.time.ToDaemon(f.t_ns), f);
    any = true;
  }
  SerialChunk c;
  while (serial_.Pop(&c)) {
    any = true;
    if (!files_) {
      discarded_.fetch_add(1, std::memory_order_relaxed);
      continue;
    }
    files_->Serial(setup_.time.ToDaemon(c.t_rx_ns), std::span(c.bytes).first(c.size));
    serial_bytes_.fetch_add(c.size, std::memory_order_relaxed);
  }
  State s;
  while (odometry_.Pop(&s)) {
    if (files_) files_->Odometry(s);
    any = true;
  }
  return any;
}

void Recorder::RecordClockOffset(int64_t now_ns) {
  if (now_ns < next_offset_check_ns_ || !files_) return;
  next_offset_check_ns_ = now_ns + 10'000'000;
  const ClockOffsetSample s = SampleClockOffset(clocks_);
  if (std::llabs(s.offset_ns - last_offset_row_ns_) > kClockOffsetRowNs) {
    files_->ClockOffset(s);
    last_offset_row_ns_ = s.offset_ns;
  }
}

void Recorder::TakeSideInputs() {
  std::vector<std::string> rows;
  std::vector<IncidentEvent> events;
  {
    std::lock_guard<std::mutex> lock(side_mutex_);
    rows.swap(health_rows_);
    events.swap(events_);
  }
  std::vector<std::string> lines;
  if (log_tap_) lines = log_tap_->Take();
  if (files_) {
    for (const std::string& r : rows) files_->HealthRow(r);
    for (const std::string& l : lines) files_->LogLine(l);
  }
  for (const IncidentEvent& e : events) store_->OnEvent(e);
  if (!events.empty() && !files_) store_->CloseAll();  // no segment will come any more
}

void Recorder::Housekeep() {
  TakeSideInputs();
  if (files_) files_->Flush();
  if (files_ && files_->failed()) StopOnFailure();
}

RingBounds Recorder::Bounds() const {
  const RecordConfig& c = setup_.config->record;
  return {SecToNs(c.ring_minutes * 60.0), static_cast<uint64_t>(c.max_disk_mb) * 1'000'000};
}

void Recorder::BoundRing(int64_t now_ns) {
  if (!ring_) return;
  const int64_t t_ns = setup_.time.ToDaemon(now_ns);
  const RingBounds bounds = Bounds();
  if (files_ && (t_ns - segment_start_ns_ >= SecToNs(setup_.config->record.segment_s) ||
                 files_->bytes() >= bounds.max_bytes / 4)) {
    Rotate(t_ns);
  }
  const uint64_t open_bytes = files_ ? files_->bytes() : 0;
  if (ring_->bytes() + open_bytes > bounds.max_bytes || now_ns >= next_trim_ns_) {
    ring_->Trim(t_ns, bounds, open_bytes, store_->KeepFromNs());
    next_trim_ns_ = now_ns + 1'000'000'000;
  }
  ring_bytes_.store(ring_->bytes() + open_bytes, std::memory_order_relaxed);
}

void Recorder::CloseSegment(int64_t t_ns) {
  const bool ok = files_->Close();
  ring_->Add({files_->dir(), segment_start_ns_, t_ns, DirectoryBytes(files_->dir())});
  if (!ok) {
    StopOnFailure();
    return;
  }
  files_.reset();
  store_->OnSegmentClosed(t_ns);
}

void Recorder::Rotate(int64_t t_ns) {
  CloseSegment(t_ns);
  if (stopped_.load()) return;
  std::string error;
  if (!OpenFolder(ring_->NextDir(), &error)) {
    std::lock_guard<std::mutex> lock(side_mutex_);
    stop_error_ = error;
    stopped_.store(true);
    spdlog::error("black box: stopped: {}", error);
    store_->CloseAll();
  }
}

void Recorder::StopOnFailure() {
  {
    std::lock_guard<std::mutex> lock(side_mutex_);
    stop_error_ = files_->error();
  }
  stopped_.store(true);
  spdlog::error("{}: stopped, nothing more is recorded: {}", ring_ ? "black box" : "recording",
                files_->error());
  files_->Close();
  files_.reset();
  if (store_) store_->CloseAll();
}

void Recorder::Finish() {
  TakeSideInputs();
  if (!ring_) {
    if (files_ && !files_->Close()) StopOnFailure();
    return;
  }
  const int64_t t_ns = setup_.time.ToDaemon(MonotonicNowNs());
  if (files_) CloseSegment(t_ns);
  store_->CloseAll();
  // The last segment's size on disk (its manifest, what it took since the last bound) is
  // known only now: the ring, the stop mark below included, ends within max_disk_mb too.
  RingBounds bounds = Bounds();
  bounds.max_bytes -= kCleanStopMarkBytes;
  ring_->Trim(t_ns, bounds, 0, store_->KeepFromNs());
  // Also after a stop on a full disk: this run's segments are no crash's (and a disk still
  // full could not hold them as an incident).
  std::ofstream(ring_dir_ / kCleanStopMark) << kCleanStopText;
}

RecorderCounters Recorder::counters() const {
  RecorderCounters c;
  c.lidar_packets = lidar_packets_.load(std::memory_order_relaxed);
  c.serial_bytes = serial_bytes_.load(std::memory_order_relaxed);
  c.discarded = discarded_.load(std::memory_order_relaxed);
  c.stopped = stopped_.load();
  c.ring = ring_ != nullptr;
  {
    std::lock_guard<std::mutex> lock(side_mutex_);
    c.error = stop_error_;
  }
  if (ring_) {
    c.segments = ring_->count();
    c.ring_bytes = ring_bytes_.load(std::memory_order_relaxed);
    c.segments_deleted = ring_->deleted();
    const int64_t oldest = ring_->oldest_start_ns();
    if (oldest != 0)
      c.ring_span_s = static_cast<double>(setup_.time.ToDaemon(MonotonicNowNs()) - oldest) * 1e-9;
  }
  if (store_) c.incidents = store_->counters();
  return c;
}

}  // namespace swlio::daemon
