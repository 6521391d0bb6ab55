#include "swlio/daemon/sensors/imu_rx.h"

#include <algorithm>

namespace swlio::daemon {

ImuRx::ImuRx(const drivers::ImuConfig& config, SpscQueue<SerialChunk>* out)
    : out_(out), driver_(config, {}) {
  driver_.SetStreamHandover(
      [this](std::span<const uint8_t> bytes, int64_t t_rx_ns, uint32_t epoch) {
        chunks_ += Push(out_, bytes, t_rx_ns, epoch);
      });
}

void ImuRx::RecordTo(SpscQueue<SerialChunk>* record) {
  record_ = record;
  driver_.SetRawSink([this](std::span<const uint8_t> bytes, int64_t t_rx_ns) {
    Push(record_, bytes, t_rx_ns, driver_.epoch());
  });
}

size_t ImuRx::Push(SpscQueue<SerialChunk>* q,
                   std::span<const uint8_t> bytes,
                   int64_t t_rx_ns,
                   uint32_t epoch) {
  size_t chunks = 0;
  while (!bytes.empty()) {  // a read longer than a chunk goes as several with its time
    const size_t n = std::min(bytes.size(), SerialChunk::kMaxBytes);
    std::copy_n(bytes.begin(), n, chunk_.bytes.begin());
    chunk_.size = static_cast<uint16_t>(n);
    chunk_.epoch = epoch;
    chunk_.t_rx_ns = t_rx_ns;
    q->Push(chunk_);  // full: dropped and counted by the queue
    ++chunks;
    bytes = bytes.subspan(n);
  }
  return chunks;
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
  bytes_.store(p.bytes_read, kRelaxed);
  chunks_published_.store(chunks_, kRelaxed);
  checksum_errors_.store(s.config_framer.checksum_errors, kRelaxed);
  skipped_bytes_.store(s.config_framer.skipped_bytes, kRelaxed);
  disconnects_.store(p.disconnects, kRelaxed);
  opens_.store(p.opens, kRelaxed);
  configurations_.store(s.configurations, kRelaxed);
  config_failures_.store(s.config_failures, kRelaxed);
}

ImuRxCounters ImuRx::counters() const {
  constexpr auto kRelaxed = std::memory_order_relaxed;
  ImuRxCounters c;
  c.bytes = bytes_.load(kRelaxed);
  c.chunks = chunks_published_.load(kRelaxed);
  c.checksum_errors = checksum_errors_.load(kRelaxed);
  c.skipped_bytes = skipped_bytes_.load(kRelaxed);
  c.disconnects = disconnects_.load(kRelaxed);
  c.opens = opens_.load(kRelaxed);
  c.configurations = configurations_.load(kRelaxed);
  c.config_failures = config_failures_.load(kRelaxed);
  c.streaming = streaming_.load(kRelaxed);
  return c;
}

}  // namespace swlio::daemon
