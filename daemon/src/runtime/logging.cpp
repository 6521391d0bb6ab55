#include "swlio/daemon/runtime/logging.h"

#include <sys/stat.h>
#include <unistd.h>

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string_view>
#include <vector>

#include <spdlog/sinks/rotating_file_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

#include "swlio/daemon/runtime/journal_sink.h"

namespace swlio::daemon {

bool StartedBySystemd(const char* journal_stream, const char* invocation_id, int stderr_fd) {
  if (journal_stream == nullptr) return invocation_id != nullptr;
  const std::string_view text(journal_stream);
  const size_t colon = text.find(':');
  if (colon == std::string_view::npos) return false;
  uint64_t device = 0;
  uint64_t inode = 0;
  const auto [dev_end, dev_ec] = std::from_chars(text.data(), text.data() + colon, device);
  const auto [ino_end, ino_ec] =
      std::from_chars(text.data() + colon + 1, text.data() + text.size(), inode);
  if (dev_ec != std::errc() || ino_ec != std::errc() || dev_end != text.data() + colon ||
      ino_end != text.data() + text.size()) {
    return false;
  }
  struct stat st {};
  return fstat(stderr_fd, &st) == 0 && static_cast<uint64_t>(st.st_dev) == device &&
         static_cast<uint64_t>(st.st_ino) == inode;
}

bool StartedBySystemd() {
  return StartedBySystemd(std::getenv("JOURNAL_STREAM"), std::getenv("INVOCATION_ID"),
                          STDERR_FILENO);
}

bool JournaldOn(const LoggingConfig& config) {
  if (config.journald == "true") return true;
  if (config.journald == "false") return false;
  return StartedBySystemd();
}

std::string EffectiveStderrLevel(const LoggingConfig& config, bool journald_on) {
  if (config.stderr_level != "auto") return config.stderr_level;
  return journald_on ? "off" : "info";
}

std::shared_ptr<spdlog::logger> SetupLogging(const LoggingConfig& config, std::string* error) {
  std::vector<spdlog::sink_ptr> sinks;
  const bool journald = JournaldOn(config);
  auto stderr_sink = std::make_shared<spdlog::sinks::stderr_sink_mt>();
  stderr_sink->set_level(spdlog::level::from_str(EffectiveStderrLevel(config, journald)));
  sinks.push_back(stderr_sink);
  if (journald) sinks.push_back(std::make_shared<JournalSink>());  // every level: journalctl -p

  if (!config.directory.empty()) {
    try {
      std::filesystem::create_directories(config.directory);
      const auto path = std::filesystem::path(config.directory) / config.file_name;
      auto file_sink = std::make_shared<spdlog::sinks::rotating_file_sink_mt>(
          path.string(), static_cast<size_t>(config.max_file_size_mb) * 1024 * 1024,
          static_cast<size_t>(config.max_files));
      file_sink->set_level(spdlog::level::from_str(config.file_level));
      sinks.push_back(file_sink);
    } catch (const std::exception& e) {  // filesystem_error or spdlog_ex
      if (error != nullptr)
        *error = "cannot open log file in '" + config.directory + "': " + e.what();
      return nullptr;
    }
  }

  auto logger = std::make_shared<spdlog::logger>("swlio", sinks.begin(), sinks.end());
  logger->set_level(spdlog::level::trace);  // the sinks filter
  logger->set_pattern(kLogPattern);
  // Status lines and faults reach the file at once (field engineers read it while it runs);
  // debug/trace output stays buffered.
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
  return logger;
}

}  // namespace swlio::daemon
