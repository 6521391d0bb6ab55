#pragma once
/// @file
/// A consumer thread's wake-up shared by all its input queues: every push rings it, the
/// consumer sleeps in Wait() until any input has data (or a timeout), then drains them all.
/// Without it a thread with two inputs sleeps on one queue and notices the other only when the
/// first gets data: the publisher saw a sweep's odometry only with the next IMU-rate pose, and
/// the optimizer saw LiDAR packets only with the next IMU sample (up to one 4 ms USB burst).
///
/// Built on the semaphore of Debian's readerwriterqueue (moodycamel, libreaderwriterqueue-dev),
/// the one the queues already sleep on: lock-free when there is no sleeper.

#include <cstdint>

#include "swlio/daemon/pipeline/moodycamel.h"

namespace swlio::daemon {

class Doorbell {
 public:
  Doorbell() = default;
  Doorbell(const Doorbell&) = delete;
  Doorbell& operator=(const Doorbell&) = delete;

  /// Any producer, any number of them.
  void Ring() { sema_.signal(); }

  /// The one consumer: true once rung (at once if rung since the last Wait), false after
  /// `timeout_us` microseconds. Clears every ring so far, so one wake-up serves a whole
  /// batch: an element pushed before a ring that Wait cleared is visible to the drain after it.
  bool Wait(int64_t timeout_us) {
    if (!sema_.wait(timeout_us)) return false;
    while (sema_.tryWait()) {
    }
    return true;
  }

 private:
  moodycamel::spsc_sema::LightweightSemaphore sema_;
};

}  // namespace swlio::daemon
