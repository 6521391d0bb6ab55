#pragma once
/// @file
/// The bounded single-producer / single-consumer queue between two daemon threads: Debian's
/// moodycamel::BlockingReaderWriterQueue (libreaderwriterqueue-dev), lock-free on both ends,
/// with a semaphore so the consumer can sleep until data arrives.
///
/// Every queue is named with its producer and consumer thread (health and logs print them).
/// The capacity is allocated in the constructor; Push never allocates (try_enqueue) and drops
/// the element when the queue is full, counting it. Counters are relaxed atomics that any
/// thread may read.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "swlio/daemon/pipeline/doorbell.h"
#include "swlio/daemon/pipeline/moodycamel.h"

namespace swlio::daemon {

/// What health reports about one queue.
struct QueueCounters {
  std::string name;
  std::string producer;
  std::string consumer;
  size_t capacity = 0;
  uint64_t pushed = 0;
  uint64_t dropped = 0;   ///< the queue was full
  size_t depth = 0;       ///< elements waiting now (approximate)
  size_t high_water = 0;  ///< largest depth the producer saw
};

template <class T>
class SpscQueue {
 public:
  SpscQueue(std::string name, std::string producer, std::string consumer, size_t capacity)
      : queue_(capacity),
        capacity_(capacity),
        name_(std::move(name)),
        producer_(std::move(producer)),
        consumer_(std::move(consumer)) {}
  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  /// Every later Push also rings `bell` (the consumer's, shared by its inputs). Call before
  /// the threads start; `bell` must outlive the queue's producer.
  void RingOnPush(Doorbell* bell) { bell_ = bell; }

  /// Producer side. False (counted) when the queue is full. The element is copied (or moved)
  /// straight into its slot.
  bool Push(T&& value) { return Count(queue_.try_enqueue(std::move(value))); }
  bool Push(const T& value) { return Count(queue_.try_enqueue(value)); }

  /// Consumer side: takes one element if there is one.
  bool Pop(T* out) { return queue_.try_dequeue(*out); }

  /// Consumer side: waits up to `timeout_us` (microseconds) for one element.
  bool WaitPop(T* out, int64_t timeout_us) { return queue_.wait_dequeue_timed(*out, timeout_us); }

  QueueCounters Counters() const {
    QueueCounters c;
    c.name = name_;
    c.producer = producer_;
    c.consumer = consumer_;
    c.capacity = capacity_;
    c.pushed = pushed_.load(std::memory_order_relaxed);
    c.dropped = dropped_.load(std::memory_order_relaxed);
    c.depth = queue_.size_approx();
    c.high_water = high_water_.load(std::memory_order_relaxed);
    return c;
  }

 private:
  bool Count(bool pushed) {
    if (!pushed) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    if (bell_ != nullptr) bell_->Ring();
    pushed_.fetch_add(1, std::memory_order_relaxed);
    const size_t depth = queue_.size_approx();
    if (depth > high_water_.load(std::memory_order_relaxed)) {
      high_water_.store(depth, std::memory_order_relaxed);
    }
    return true;
  }

  // In clang-tidy's padding order (moodycamel aligns its indices to cache lines).
  moodycamel::BlockingReaderWriterQueue<T> queue_;
  size_t capacity_;
  Doorbell* bell_ = nullptr;
  std::atomic<uint64_t> pushed_{0};
  std::atomic<uint64_t> dropped_{0};
  std::atomic<size_t> high_water_{0};
  std::string name_;
  std::string producer_;
  std::string consumer_;
};

}  // namespace swlio::daemon
