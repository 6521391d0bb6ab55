#pragma once
/// @file
/// Joins consecutive recording folders (the ring's segments) into one, so an incident is a
/// plain recording that swlio-run, swlio-replay and swlio-report read as they are: lidar.pcap
/// records follow each other (one global header), imu.xbus bytes likewise with imu.rx.csv's
/// byte offsets moved on, the CSV files keep one header, the text files follow each other;
/// manifest.yaml and config.yaml are the first folder's (one daemon run: they are the same).

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace swlio::daemon {

/// Writes `out` (created; must not exist) from `parts`, oldest first. `progress` is called
/// after every MiB copied (the caller's watchdog beat). False with `error` on the first
/// failure; `out` may then hold part of it.
bool ConcatenateRecordings(const std::vector<std::filesystem::path>& parts,
                           const std::filesystem::path& out,
                           const std::function<void()>& progress,
                           std::string* error);

}  // namespace swlio::daemon
