#pragma once
/// @file
/// The lidar_rx thread: receives the LiDAR's MSOP and DIFOP datagrams (two UDP sockets, one
/// poll), stamps them with the kernel receive time and pushes them, undecoded, to the
/// optimizer thread's queue. Allocates nothing after Open(). A full queue drops the datagram
/// (counted by the queue). After each batch it sleeps `lidar.rx_batch_ms`, so that a wake-up
/// takes several datagrams: at one per datagram (750/s) the wake-ups, its own and the
/// optimizer's, cost 0.03 core of kernel time (measured live, `aggressive` at 1×).

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/runtime/latency_histogram.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/drivers/lidar_config.h"
#include "swlio/drivers/udp_receiver.h"

namespace swlio::daemon {

/// Totals over both sockets, readable from any thread.
struct LidarRxCounters {
  uint64_t datagrams = 0;
  uint64_t truncated = 0;  ///< longer than LidarPacket::kMaxBytes
  uint64_t errors = 0;     ///< poll / recvmmsg failures
  uint64_t stamp_fallbacks = 0;
  /// From each datagram's kernel receive stamp to the recvmmsg(2) that took it.
  LatencyHistogram::Counts read_lag{};
};

class LidarRx {
 public:
  static std::unique_ptr<LidarRx> Open(const drivers::LidarConfig& config,
                                       SpscQueue<LidarPacket>* out,
                                       std::string* error);
  /// Receives until `stop` is set, beating `beat` at least every 100 ms.
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  LidarRxCounters counters() const;
  /// Also pushes every datagram to `record` (the recorder's queue); call before Run.
  void RecordTo(SpscQueue<LidarPacket>* record) { record_ = record; }
  uint16_t msop_port() const { return msop_->bound_port(); }
  uint16_t difop_port() const { return difop_->bound_port(); }
  int64_t rcvbuf_granted() const { return msop_->rcvbuf_granted(); }

 private:
  LidarRx() = default;
  void Drain(drivers::UdpReceiver& receiver, bool difop);
  void Publish();

  std::optional<drivers::UdpReceiver> msop_;
  std::optional<drivers::UdpReceiver> difop_;
  SpscQueue<LidarPacket>* out_ = nullptr;
  SpscQueue<LidarPacket>* record_ = nullptr;
  int64_t batch_ns_ = 0;
  LidarPacket packet_;
  uint64_t truncated_ = 0;
  uint64_t poll_errors_ = 0;
  std::atomic<uint64_t> datagrams_{0};
  std::atomic<uint64_t> truncated_total_{0};
  std::atomic<uint64_t> errors_{0};
  std::atomic<uint64_t> stamp_fallbacks_{0};
  LatencyHistogram read_lag_;
};

}  // namespace swlio::daemon
