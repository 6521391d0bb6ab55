#include "test_data.h"

#include <unistd.h>
#include <atomic>
#include <cstdlib>

namespace swlio::test {

std::filesystem::path DataDir() {
  if (const char* env = std::getenv("SWLIO_DATA_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return SWLIO_DEFAULT_DATA_DIR;
}

std::filesystem::path DataFile(const std::string& relative) {
  std::filesystem::path p = DataDir() / relative;
  std::error_code ec;
  return std::filesystem::exists(p, ec) ? p : std::filesystem::path{};
}

std::filesystem::path SourceDir() {
  if (const char* env = std::getenv("SWLIO_SOURCE_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return SWLIO_SOURCE_DIR;
}

std::filesystem::path MakeTempDir(const std::string& tag) {
  static std::atomic<int> counter{0};
  const auto dir =
      std::filesystem::temp_directory_path() / ("swlio_" + tag + "_" + std::to_string(::getpid()) +
                                                "_" + std::to_string(counter.fetch_add(1)));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace swlio::test
