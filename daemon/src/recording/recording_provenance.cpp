#include "swlio/daemon/recording/recording_provenance.h"

#include <fstream>

namespace swlio::daemon {

std::optional<std::filesystem::path> RecordedConfigFile(const std::filesystem::path& dir) {
  std::error_code ec;
  const std::filesystem::path p = dir / "config.yaml";
  if (std::filesystem::is_regular_file(p, ec)) return p;
  return std::nullopt;
}

std::string RecordedVersion(const std::filesystem::path& dir) {
  std::ifstream in(dir / "manifest.yaml");
  std::string line;
  const std::string key = "swlio_version:";
  while (std::getline(in, line)) {
    if (line.rfind(key, 0) != 0) continue;
    std::string v = line.substr(key.size());
    v.erase(0, v.find_first_not_of(" \t"));
    if (v.size() >= 2 && v.front() == '"' && v.back() == '"') v = v.substr(1, v.size() - 2);
    return v;
  }
  return {};
}

std::string VersionNote(const std::filesystem::path& dir, const std::string& this_version) {
  const std::string recorded = RecordedVersion(dir);
  if (recorded.empty()) return {};
  if (recorded == this_version) return "recorded by this version (" + recorded + ")";
  return "recorded by swlio " + recorded + ", replayed by " + this_version +
         ": decoders, clocks or estimator may differ, so may the trajectory";
}

}  // namespace swlio::daemon
