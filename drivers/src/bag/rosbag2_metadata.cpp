// The keys of rosbag2's metadata.yaml that reading needs (rosbag2_metadata.h).

#include "swlio/drivers/bag/rosbag2_metadata.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string_view>

namespace swlio::drivers::bag {
namespace {

/// A scalar as yaml-cpp emits it: bare, or in double quotes (rosbag2 quotes empty strings).
std::string Scalar(std::string_view v) {
  while (!v.empty() && (v.back() == ' ' || v.back() == '\r')) v.remove_suffix(1);
  if (v.size() >= 2 && v.front() == '"' && v.back() == '"') v = v.substr(1, v.size() - 2);
  if (v.size() >= 2 && v.front() == '\'' && v.back() == '\'') v = v.substr(1, v.size() - 2);
  return std::string(v);
}

/// `line` is "<indent>key: value"; returns true and the value when the key matches.
bool KeyValue(std::string_view line, std::string_view key, std::string* value) {
  const std::string prefix = "  " + std::string(key) + ":";
  if (line.substr(0, prefix.size()) != prefix) return false;
  *value = Scalar(line.substr(std::min(line.size(), prefix.size() + 1)));
  return true;
}

}  // namespace

bool ReadRosbag2Metadata(const std::filesystem::path& path,
                         Rosbag2Metadata* out,
                         std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path.string() + ": cannot read";
    return false;
  }
  bool root = false;
  bool in_files = false;
  std::string value;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("rosbag2_bagfile_information:", 0) == 0) root = true;
    if (!root) continue;
    if (in_files && line.rfind("    - ", 0) == 0) {
      out->relative_file_paths.push_back(Scalar(std::string_view(line).substr(6)));
      continue;
    }
    in_files = false;
    if (KeyValue(line, "version", &value)) {
      out->version = std::atoi(value.c_str());
    } else if (KeyValue(line, "storage_identifier", &value)) {
      out->storage_identifier = value;
    } else if (KeyValue(line, "compression_format", &value)) {
      out->compression_format = value;
    } else if (KeyValue(line, "compression_mode", &value)) {
      out->compression_mode = value;
    } else if (KeyValue(line, "relative_file_paths", &value)) {
      in_files = true;
    }
  }
  if (!root) {
    *error = path.string() + ": no 'rosbag2_bagfile_information' key (not rosbag2 metadata)";
    return false;
  }
  return true;
}

}  // namespace swlio::drivers::bag
