#pragma once
/// @file
/// A spdlog sink that keeps the formatted log lines (the log file's pattern) until the recorder
/// takes them into the black box's log.txt. Bounded: when nobody takes them (the ring stopped)
/// the oldest go, counted.

#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <spdlog/sinks/base_sink.h>

namespace swlio::daemon {

class LogTap : public spdlog::sinks::base_sink<std::mutex> {
 public:
  explicit LogTap(size_t capacity = 20000) : capacity_(capacity) {}
  /// Every line since the last call, oldest first (no newlines).
  std::vector<std::string> Take();
  uint64_t dropped() const;

  /// The tap of the "swlio" logger, added to it once (null when no logger exists).
  static std::shared_ptr<LogTap> Attach();
  /// Takes `tap` off the logger again. Attach and Detach only while no other thread logs.
  static void Detach(const std::shared_ptr<LogTap>& tap);

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override;
  void flush_() override {}

 private:
  mutable std::mutex lines_mutex_;
  std::deque<std::string> lines_;
  uint64_t dropped_ = 0;
  size_t capacity_;
};

}  // namespace swlio::daemon
