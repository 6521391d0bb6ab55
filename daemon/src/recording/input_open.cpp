#include "swlio/daemon/recording/input_open.h"

#include <filesystem>

namespace swlio::daemon {
namespace {

/// A file (any: OpenBag tells what it is), or a folder with what a rosbag2 folder holds.
bool LooksLikeBag(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return true;
  for (const fs::directory_entry& e : fs::directory_iterator(path, ec)) {
    const std::string ext = e.path().extension().string();
    if (e.path().filename() == "metadata.yaml" || ext == ".db3" || ext == ".mcap") return true;
  }
  return false;
}

}  // namespace

std::unique_ptr<SensorInput> OpenSensorInput(const std::string& path,
                                             const drivers::LidarConfig& lidar,
                                             const drivers::ImuConfig& imu,
                                             const SensorInputOptions& options,
                                             std::string* error) {
  if (IsRecordingFolder(path)) {
    return RecordingReader::Open(path, WithManifestPorts(path, lidar), imu, options.recording,
                                 error);
  }
  if (!LooksLikeBag(path)) {
    *error = path + ": neither a recording folder (manifest.yaml, lidar.pcap, imu.xbus) nor a " +
             "rosbag2 folder (metadata.yaml, .db3 or .mcap files)";
    return nullptr;
  }
  return OpenBagInput(path, lidar, options.bag, error);
}

}  // namespace swlio::daemon
