#include "swlio/daemon/sensors/can_rx.h"

#include <chrono>
#include <thread>
#include <utility>
#include <vector>

namespace swlio::daemon {

std::unique_ptr<CanRx> CanRx::Create(const drivers::CanConfig& config, int fd, std::string* error) {
  ConfigIssues issues;
  std::optional<drivers::WheelOdomDecoder> decoder =
      drivers::WheelOdomDecoder::Create(config, &issues);
  if (!decoder) {
    *error = "can: the signal layout cannot be decoded";
    for (const ConfigIssue& i : issues) *error += "; " + i.key + ": " + i.reason;
    return nullptr;
  }
  std::vector<drivers::CanIdFilter> filters;
  for (int i = 0; i < decoder->NumIds(); ++i) {
    const drivers::CompiledCanSignal& s = decoder->IdSignal(i);
    filters.push_back(
        {s.id, s.extended, s.extended ? drivers::kCanMaxExtendedId : drivers::kCanMaxStandardId});
  }
  return std::unique_ptr<CanRx>(new CanRx(fd, filters, *decoder));
}

CanRx::CanRx(int fd,
             std::span<const drivers::CanIdFilter> filters,
             const drivers::WheelOdomDecoder& decoder)
    : reader_(fd, filters), decoder_(decoder) {}

void CanRx::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    const int n = reader_.Read(frames_, 100);
    if (n < 0) {  // the interface is gone: keep beating (health says closed), stop reading
      Publish(true);
      while (!stop.load(std::memory_order_relaxed)) {
        beat.Beat();
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
      return;
    }
    for (int i = 0; i < n; ++i) {
      const drivers::CanRxFrame& f = frames_[static_cast<size_t>(i)];
      const std::optional<drivers::WheelOdomSample> s = decoder_.Decode(f.frame, f.t_ns);
      if (s && wheel_ != nullptr) {
        wheel_->Push(WheelOdometry{s->t_ns, s->linear_velocity_mps, s->yaw_rate_radps});
      }
      if (record_ != nullptr) record_->Push(f);
    }
    Publish(false);
  }
}

void CanRx::Publish(bool closed) {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  const drivers::CanReaderCounters& r = reader_.counters();
  const drivers::WheelOdomCounters& d = decoder_.counters();
  frames_n_.store(r.frames, kRelaxed);
  samples_.store(d.samples, kRelaxed);
  unknown_.store(d.unknown_id + r.filtered_out, kRelaxed);
  bad_.store(r.bad_size + d.bad_dlc + d.remote_or_error, kRelaxed);
  errors_.store(r.read_errors, kRelaxed);
  closed_.store(closed, kRelaxed);
}

CanRxCounters CanRx::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  CanRxCounters c;
  c.frames = frames_n_.load(kRelaxed);
  c.odometry_samples = samples_.load(kRelaxed);
  c.unknown_id = unknown_.load(kRelaxed);
  c.bad_frames = bad_.load(kRelaxed);
  c.read_errors = errors_.load(kRelaxed);
  c.closed = closed_.load(kRelaxed);
  return c;
}

}  // namespace swlio::daemon
