#pragma once
/// @file
/// A control command handed from the control thread to the thread that owns what it acts on
/// (save-map: loop_closure, which owns the pose graph; reset: optimizer, which owns the
/// estimator), and its answer back. The request travels in that thread's SpscQueue (control →
/// owner); the owner calls Finish once; the control thread polls Result() without blocking and
/// gives up after control.command_timeout_s (Cancel: a command not started yet is skipped).

#include <atomic>
#include <mutex>
#include <optional>
#include <string>

#include "swlio/control/protocol.h"

namespace swlio::daemon {

class PendingCommand {
 public:
  explicit PendingCommand(control::Request request) : request_(std::move(request)) {}

  const control::Request& request() const { return request_; }

  // --- the owning thread ---
  /// The control thread gave up waiting: do not start it.
  bool cancelled() const { return cancelled_.load(std::memory_order_acquire); }
  /// The outcome (once).
  void Finish(control::Reply reply) {
    std::lock_guard<std::mutex> lock(mutex_);
    reply_ = std::move(reply);
  }

  // --- the control thread ---
  std::optional<control::Reply> Result() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return reply_;
  }
  void Cancel() { cancelled_.store(true, std::memory_order_release); }

 private:
  const control::Request request_;
  std::atomic<bool> cancelled_{false};
  mutable std::mutex mutex_;
  std::optional<control::Reply> reply_;
};

}  // namespace swlio::daemon
