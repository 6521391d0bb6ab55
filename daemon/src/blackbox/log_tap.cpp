#include "swlio/daemon/blackbox/log_tap.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "swlio/daemon/runtime/logging.h"

namespace swlio::daemon {

void LogTap::sink_it_(const spdlog::details::log_msg& msg) {
  spdlog::memory_buf_t formatted;
  formatter_->format(msg, formatted);
  std::string line(formatted.data(), formatted.size());
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
  std::lock_guard<std::mutex> lock(lines_mutex_);
  if (lines_.size() >= capacity_) {
    lines_.pop_front();
    ++dropped_;
  }
  lines_.push_back(std::move(line));
}

std::vector<std::string> LogTap::Take() {
  std::lock_guard<std::mutex> lock(lines_mutex_);
  std::vector<std::string> out(std::make_move_iterator(lines_.begin()),
                               std::make_move_iterator(lines_.end()));
  lines_.clear();
  return out;
}

uint64_t LogTap::dropped() const {
  std::lock_guard<std::mutex> lock(lines_mutex_);
  return dropped_;
}

std::shared_ptr<LogTap> LogTap::Attach() {
  std::shared_ptr<spdlog::logger> logger = spdlog::get("swlio");
  if (!logger) logger = spdlog::default_logger();
  if (!logger) return nullptr;
  auto tap = std::make_shared<LogTap>();
  tap->set_pattern(kLogPattern);  // log.txt reads like swliod.log
  tap->set_level(spdlog::level::info);
  logger->sinks().push_back(tap);
  return tap;
}

void LogTap::Detach(const std::shared_ptr<LogTap>& tap) {
  if (!tap) return;
  std::shared_ptr<spdlog::logger> logger = spdlog::get("swlio");
  if (!logger) logger = spdlog::default_logger();
  if (!logger) return;
  std::vector<spdlog::sink_ptr>& sinks = logger->sinks();
  sinks.erase(std::remove(sinks.begin(), sinks.end(), tap), sinks.end());
}

}  // namespace swlio::daemon
