#pragma once
/// @file
/// The imu_rx thread: drives the supervised Xsens serial driver (open → configure → stream,
/// re-open after an unplug) and pushes each MTData2 sample's time fields and inertial items
/// with the host receive time to the propagator thread's queue. No allocation after start-up.

#include <atomic>
#include <cstdint>

#include "swlio/daemon/pipeline/spsc_queue.h"
#include "swlio/daemon/recording/recorder.h"
#include "swlio/daemon/runtime/watchdog.h"
#include "swlio/daemon/sensors/imu_stage.h"
#include "swlio/drivers/imu_config.h"
#include "swlio/drivers/xsens/xsens_serial_driver.h"

namespace swlio::daemon {

/// What health reports about the serial side, readable from any thread.
struct ImuRxCounters {
  uint64_t samples = 0;
  uint64_t bytes = 0;
  uint64_t checksum_errors = 0;
  uint64_t skipped_bytes = 0;    ///< bytes the framer skipped resynchronizing (garbage)
  uint64_t missing_packets = 0;  ///< PacketCounter gaps
  uint64_t disconnects = 0;
  uint64_t opens = 0;
  uint64_t configurations = 0;
  uint64_t config_failures = 0;
  bool streaming = false;
};

class ImuRx {
 public:
  ImuRx(const drivers::ImuConfig& config, SpscQueue<ImuRaw>* out);
  /// Reads until `stop` is set, beating `beat` at least every 100 ms.
  void Run(const std::atomic<bool>& stop, const Watchdog::Handle& beat);
  ImuRxCounters counters() const;
  /// Also pushes every chunk of bytes read to `record` (the recorder's queue); before Run.
  void RecordTo(SpscQueue<SerialChunk>* record);

 private:
  void Publish();

  SpscQueue<ImuRaw>* out_;
  SpscQueue<SerialChunk>* record_ = nullptr;
  SerialChunk chunk_;
  drivers::xsens::XsensSerialDriver driver_;
  std::atomic<uint64_t> samples_{0}, bytes_{0}, checksum_errors_{0}, skipped_bytes_{0},
      missing_packets_{0}, disconnects_{0}, opens_{0}, configurations_{0}, config_failures_{0};
  std::atomic<bool> streaming_{false};
};

}  // namespace swlio::daemon
