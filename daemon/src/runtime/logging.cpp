#include "swlio/daemon/runtime/logging.h"

#include <filesystem>
#include <vector>

#include <spdlog/sinks/rotating_file_sink.h>
#include <spdlog/sinks/stdout_sinks.h>
#include <spdlog/spdlog.h>

namespace swlio::daemon {

std::shared_ptr<spdlog::logger> SetupLogging(const LoggingConfig& config, std::string* error) {
  std::vector<spdlog::sink_ptr> sinks;
  auto stderr_sink = std::make_shared<spdlog::sinks::stderr_sink_mt>();
  stderr_sink->set_level(spdlog::level::from_str(config.stderr_level));
  sinks.push_back(stderr_sink);

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
