#pragma once
/// @file
/// Where operators' pose hints (pose_hint.h) arrive for the thread that applies them (the
/// localization thread in a saved map, the loop-closure thread while mapping): swlioctl's
/// relocalize through a small queue from the control thread, /initialpose through a DDS reader
/// the owning thread polls. A message in another frame or not a pose is logged and counted.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "swlio/daemon/pipeline/pose_hint.h"
#include "swlio/daemon/pipeline/spsc_queue.h"

namespace swlio::ipc {
class Subscriber;
}

namespace swlio::daemon {

class HintInbox {
 public:
  explicit HintInbox(const char* consumer) : requests_{"hint_requests", "control", consumer, 4} {}
  /// /initialpose through `reader` (not owned; its pose topic is the hint topic), whose frame
  /// must be `map_frame`. Call before the owning thread runs.
  void ReadFrom(ipc::Subscriber* reader, const std::string& map_frame) {
    reader_ = reader;
    map_frame_ = map_frame;
  }
  /// A swlioctl hint (control thread only). False when requests are already queued.
  bool Request(PoseHint hint) { return requests_.Push(std::move(hint)); }
  /// Hands every hint that arrived to `apply` (owning thread), swlioctl's first.
  void Drain(const std::function<void(const PoseHint&)>& apply);
  /// Answers the queued requests "failed" (the daemon stops).
  void FailQueued();
  uint64_t unreadable() const { return unreadable_.load(std::memory_order_relaxed); }

 private:
  SpscQueue<PoseHint> requests_;
  ipc::Subscriber* reader_ = nullptr;
  std::string map_frame_ = "map";
  std::atomic<uint64_t> unreadable_{0};
};

}  // namespace swlio::daemon
