#pragma once
/// @file
/// The few keys of a rosbag2 `metadata.yaml` that reading needs: which storage, which files in
/// which order (split bags), and whether rosbag2 compressed messages or files
/// (ros2/rosbag2 rosbag2_storage/include/rosbag2_storage/yaml.hpp at 25304dd; research/bags.md
/// §1.2). rosbag2 writes this file with yaml-cpp's emitter in a fixed layout: the root key
/// `rosbag2_bagfile_information:`, its keys indented by two spaces, list items of
/// `relative_file_paths` by four. Only those lines are read, the way the daemon's recording
/// reader reads its manifest, so the drivers library stays free of a YAML dependency (the
/// layering rule of ARCHITECTURE.md); every other key is ignored.

#include <filesystem>
#include <string>
#include <vector>

namespace swlio::drivers::bag {

struct Rosbag2Metadata {
  int version = 0;
  std::string storage_identifier;                ///< "sqlite3" or "mcap"
  std::vector<std::string> relative_file_paths;  ///< in recording order
  std::string compression_format;                ///< "" or "zstd"
  std::string compression_mode;                  ///< "", "FILE" or "MESSAGE" (any case)
};

/// Reads `path`. False with `error` (naming the file) when it cannot be read or lacks the root
/// key; missing keys stay empty.
bool ReadRosbag2Metadata(const std::filesystem::path& path,
                         Rosbag2Metadata* out,
                         std::string* error);

}  // namespace swlio::drivers::bag
