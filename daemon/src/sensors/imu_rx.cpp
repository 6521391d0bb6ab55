#include "swlio/daemon/sensors/imu_rx.h"

#include <algorithm>

namespace swlio::daemon {

ImuRx::ImuRx(const drivers::ImuConfig& config, SpscQueue<ImuRaw>* out)
    : out_(out),
      driver_(config, [this](const drivers::xsens::MtData2Sample& sample, int64_t t_host_ns) {
        out_->Push(ToImuRaw(sample, t_host_ns, driver_.last_frame_bytes()));
      }) {}

void ImuRx::RecordTo(SpscQueue<SerialChunk>* record) {
  record_ = record;
  driver_.SetRawSink([this](std::span<const uint8_t> bytes, int64_t t_host_ns) {
    while (!bytes.empty()) {  // a read longer than a chunk goes as several with its time
      const size_t n = std::min(bytes.size(), SerialChunk::kMaxBytes);
      std::copy_n(bytes.begin(), n, chunk_.bytes.begin());
      chunk_.size = static_cast<uint16_t>(n);
      chunk_.t_rx_ns = t_host_ns;
      record_->Push(chunk_);
      bytes = bytes.subspan(n);
    }
  });
}

void ImuRx::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  constexpr int64_t kPollNs = 100'000'000;
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    const drivers::xsens::XsensDriverState state = driver_.Poll(kPollNs);
    streaming_.store(state == drivers::xsens::XsensDriverState::kStream, std::memory_order_relaxed);
    Publish();
  }
}

void ImuRx::Publish() {
  const drivers::xsens::XsensDriverStats& s = driver_.stats();
  const drivers::SerialPortStats& p = driver_.port().stats();
  constexpr auto kRelaxed = std::memory_order_relaxed;
  samples_.store(s.samples, kRelaxed);
  bytes_.store(p.bytes_read, kRelaxed);
  checksum_errors_.store(s.framer.checksum_errors, kRelaxed);
  skipped_bytes_.store(s.framer.skipped_bytes, kRelaxed);
  missing_packets_.store(s.missing_packets, kRelaxed);
  disconnects_.store(p.disconnects, kRelaxed);
  opens_.store(p.opens, kRelaxed);
  configurations_.store(s.configurations, kRelaxed);
  config_failures_.store(s.config_failures, kRelaxed);
}

ImuRxCounters ImuRx::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  ImuRxCounters c;
  c.samples = samples_.load(kRelaxed);
  c.bytes = bytes_.load(kRelaxed);
  c.checksum_errors = checksum_errors_.load(kRelaxed);
  c.skipped_bytes = skipped_bytes_.load(kRelaxed);
  c.missing_packets = missing_packets_.load(kRelaxed);
  c.disconnects = disconnects_.load(kRelaxed);
  c.opens = opens_.load(kRelaxed);
  c.configurations = configurations_.load(kRelaxed);
  c.config_failures = config_failures_.load(kRelaxed);
  c.streaming = streaming_.load(kRelaxed);
  return c;
}

}  // namespace swlio::daemon
