#pragma once
/// @file
/// What a daemon recording (swliod --record, a black-box segment or incident) says about the
/// daemon that made it: its configuration (config.yaml) and version (manifest.yaml's
/// `swlio_version:`), so that swlio-replay reproduces that run and says when it cannot.

#include <filesystem>
#include <optional>
#include <string>

namespace swlio::daemon {

/// config.yaml in `dir`, when there is one.
std::optional<std::filesystem::path> RecordedConfigFile(const std::filesystem::path& dir);

/// The manifest's `swlio_version:` ("" when absent: the simulator's or an older recording).
std::string RecordedVersion(const std::filesystem::path& dir);

/// One line comparing RecordedVersion with this build's: "" when the recording states none.
std::string VersionNote(const std::filesystem::path& dir, const std::string& this_version);

}  // namespace swlio::daemon
