#include "swlio/daemon/sensors/lidar_rx.h"

#include <poll.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>
#include <utility>

namespace swlio::daemon {
namespace {

std::optional<drivers::UdpReceiver> OpenPort(const drivers::LidarConfig& config,
                                             uint16_t port,
                                             std::string* error) {
  drivers::UdpReceiverOptions o;
  o.bind_address = config.bind_address;
  o.port = port;
  o.rcvbuf_bytes = config.rcvbuf_bytes;
  o.max_datagram_bytes = LidarPacket::kMaxBytes + 1;  // one byte more tells "too long"
  return drivers::UdpReceiver::Open(o, error);
}

}  // namespace

std::unique_ptr<LidarRx> LidarRx::Open(const drivers::LidarConfig& config,
                                       SpscQueue<LidarPacket>* out,
                                       std::string* error) {
  std::unique_ptr<LidarRx> rx(new LidarRx());
  rx->out_ = out;
  rx->batch_ns_ = config.rx_batch_ms * 1'000'000;
  std::optional<drivers::UdpReceiver> msop = OpenPort(config, config.msop_port, error);
  if (!msop) return nullptr;
  std::optional<drivers::UdpReceiver> difop = OpenPort(config, config.difop_port, error);
  if (!difop) return nullptr;
  rx->msop_.emplace(std::move(*msop));  // UdpReceiver is move-constructible only
  rx->difop_.emplace(std::move(*difop));
  return rx;
}

void LidarRx::Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat) {
  pollfd fds[2] = {{msop_->fd(), POLLIN, 0}, {difop_->fd(), POLLIN, 0}};
  while (!stop.load(std::memory_order_relaxed)) {
    beat.Beat();
    fds[0].revents = fds[1].revents = 0;
    const int n = poll(fds, 2, 100);
    if (n < 0 && errno != EINTR) ++poll_errors_;
    if (n <= 0) continue;
    if (fds[0].revents != 0) Drain(*msop_, false);
    if (fds[1].revents != 0) Drain(*difop_, true);
    Publish();
    if (batch_ns_ > 0) std::this_thread::sleep_for(std::chrono::nanoseconds(batch_ns_));
  }
}

void LidarRx::Drain(drivers::UdpReceiver& receiver, bool difop) {
  const std::span<const drivers::ReceivedDatagram> batch = receiver.Receive(0);
  const int64_t now_ns = batch.empty() ? 0 : MonotonicNowNs();
  for (const drivers::ReceivedDatagram& d : batch) {
    read_lag_.Add(now_ns - d.t_ns);
    if (d.truncated || d.payload.size() > LidarPacket::kMaxBytes) {
      ++truncated_;
      continue;
    }
    packet_.size = static_cast<uint16_t>(d.payload.size());
    std::memcpy(packet_.bytes.data(), d.payload.data(), d.payload.size());
    packet_.t_rx_ns = d.t_ns;
    packet_.difop = difop;
    out_->Push(packet_);
    if (record_ != nullptr) record_->Push(packet_);
  }
}

void LidarRx::Publish() {
  const drivers::UdpReceiverCounters& a = msop_->counters();
  const drivers::UdpReceiverCounters& b = difop_->counters();
  datagrams_.store(a.datagrams + b.datagrams, std::memory_order_relaxed);
  truncated_total_.store(truncated_, std::memory_order_relaxed);
  errors_.store(a.errors + b.errors + poll_errors_, std::memory_order_relaxed);
  stamp_fallbacks_.store(a.stamp_fallbacks + b.stamp_fallbacks, std::memory_order_relaxed);
}

LidarRxCounters LidarRx::counters() const {
  LidarRxCounters c;
  c.datagrams = datagrams_.load(std::memory_order_relaxed);
  c.truncated = truncated_total_.load(std::memory_order_relaxed);
  c.errors = errors_.load(std::memory_order_relaxed);
  c.stamp_fallbacks = stamp_fallbacks_.load(std::memory_order_relaxed);
  c.read_lag = read_lag_.Snapshot();
  return c;
}

}  // namespace swlio::daemon
