#pragma once
/// @file
/// The imu_rx thread: drives the supervised Xsens serial driver (open → configure → stream,
/// re-open after an unplug) and, while it streams, only reads, stamps and hands over: every
/// read's bytes go, with the host time of the read and the port's open epoch, as SerialChunks
/// to the propagator thread, which frames and decodes them (XsensStreamDecoder) before the
/// clock model. The configuration handshake at each open (no sensor data flows then) is
/// framed and answered here. A full queue drops and counts (the queue's counters); the thread
/// never blocks on it. No allocation after start-up.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>

#include "swlio/daemon/pipeline/live_types.h"
#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/drivers/imu_config.h"
#include "swlio/drivers/xsens/xsens_serial_driver.h"

namespace swlio::daemon {

/// What health reports about the serial side, readable from any thread. The stream's decoding
/// counters (samples, gaps, the stream's checksum errors) are the propagator's
/// (PropagatorCounters::decode).
struct ImuRxCounters {
  uint64_t bytes = 0;            ///< read from the port
  uint64_t chunks = 0;           ///< stream chunks offered to the propagator's queue
  uint64_t checksum_errors = 0;  ///< while configuring
  uint64_t skipped_bytes = 0;    ///< while configuring: bytes skipped resynchronizing
  uint64_t disconnects = 0;
  uint64_t opens = 0;
  uint64_t configurations = 0;
  uint64_t config_failures = 0;
  bool streaming = false;
};

class ImuRx {
 public:
  /// `out`: imu_rx → propagator, the stream's bytes.
  ImuRx(const drivers::ImuConfig& config, SpscQueue<SerialChunk>* out);
  /// Reads until `stop` is set, beating `beat` at least every 100 ms.
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  ImuRxCounters counters() const;
  /// Also pushes every chunk of bytes read (the handshakes' too) to `record` (the recorder's
  /// queue); before Run.
  void RecordTo(SpscQueue<SerialChunk>* record);

 private:
  /// Pushes `bytes` to `q` as chunks of at most SerialChunk::kMaxBytes, each with `t_rx_ns`
  /// and `epoch`; returns how many chunks were offered.
  size_t Push(SpscQueue<SerialChunk>* q,
              std::span<const uint8_t> bytes,
              int64_t t_rx_ns,
              uint32_t epoch);
  void Publish();

  SpscQueue<SerialChunk>* out_;
  SpscQueue<SerialChunk>* record_ = nullptr;
  SerialChunk chunk_;  ///< staging for Push (a queue slot is written by copy)
  uint64_t chunks_ = 0;
  drivers::xsens::XsensSerialDriver driver_;
  std::atomic<uint64_t> bytes_{0}, chunks_published_{0}, checksum_errors_{0}, skipped_bytes_{0},
      disconnects_{0}, opens_{0}, configurations_{0}, config_failures_{0};
  std::atomic<bool> streaming_{false};
};

}  // namespace swlio::daemon
