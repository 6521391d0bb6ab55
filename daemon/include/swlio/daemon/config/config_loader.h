#pragma once
/// @file
/// The one place YAML becomes a DaemonConfig.
///
/// Rules: every key is optional (in-class defaults) except `config_version`; unknown keys are
/// errors (with a "did you mean" hint), and so are removed keys (with what replaced them);
/// values must have the field's type; then every module's `Validate()` runs. All problems are
/// collected, each with file, line, column, key and reason, so one run of `swliod --check-config`
/// lists everything that is wrong.

#include <filesystem>
#include <string>
#include <vector>

#include "swlio/daemon/config/daemon_config.h"

namespace swlio::daemon {

struct ConfigError {
  std::string file;
  int line = 0;     ///< 1-based; 0 when the key is absent from the file (a default was used)
  int column = 0;   ///< 1-based; 0 when unknown
  std::string key;  ///< dotted path, e.g. "lidar.max_range_m"; empty for file-level errors
  std::string reason;

  /// "file:line:column: key: reason" (the form editors and compilers use).
  std::string ToString() const;
};

struct LoadedConfig {
  DaemonConfig config;
  std::vector<ConfigError> errors;

  bool ok() const { return errors.empty(); }
  /// All errors, one per line.
  std::string ErrorReport() const;
};

/// Loads and validates a YAML file. Relative paths inside it (log directory, DDS XML) are
/// resolved against the file's directory.
LoadedConfig LoadConfigFile(const std::filesystem::path& path);

/// Same as LoadConfigFile for text already in memory; `display_name` names it in messages and
/// `base_dir` resolves relative paths (swliod gives standard input the current directory).
LoadedConfig LoadConfigText(const std::string& yaml_text,
                            const std::string& display_name,
                            const std::filesystem::path& base_dir);

}  // namespace swlio::daemon
