#include "test_data.h"

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <system_error>
#include <vector>

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

namespace {

/// The folders MakeTempDir made, removed when the test process exits (a test's outputs are
/// seconds of sensor data each; they used to pile up in /tmp). SWLIO_KEEP_TEST_DIRS=1 keeps them.
class TempDirRegistry {
 public:
  void Add(const std::filesystem::path& dir) {
    std::lock_guard<std::mutex> lock(mutex_);
    dirs_.push_back(dir);
  }
  ~TempDirRegistry() {
    if (std::getenv("SWLIO_KEEP_TEST_DIRS") != nullptr || ::getpid() != pid_) return;
    std::error_code ec;
    for (const auto& dir : dirs_) std::filesystem::remove_all(dir, ec);
  }
  TempDirRegistry() = default;
  TempDirRegistry(const TempDirRegistry&) = delete;
  TempDirRegistry& operator=(const TempDirRegistry&) = delete;

 private:
  std::mutex mutex_;
  std::vector<std::filesystem::path> dirs_;
  pid_t pid_ = ::getpid();  ///< a forked child must not remove its parent's folders
};

TempDirRegistry& TempDirs() {
  static TempDirRegistry registry;
  return registry;
}

}  // namespace

std::filesystem::path MakeTempDir(const std::string& tag) {
  static std::atomic<int> counter{0};
  const auto dir =
      std::filesystem::temp_directory_path() / ("swlio_" + tag + "_" + std::to_string(::getpid()) +
                                                "_" + std::to_string(counter.fetch_add(1)));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  TempDirs().Add(dir);
  return dir;
}

std::filesystem::path ToolPath(const std::string& name) {
  const std::filesystem::path tool =
      std::filesystem::read_symlink("/proc/self/exe").parent_path() / name;
  return std::filesystem::exists(tool) ? tool : std::filesystem::path{};
}

std::string RunCommand(const std::string& command, int* exit_code) {
  std::string out;
  std::FILE* p = ::popen(command.c_str(), "r");
  if (p == nullptr) {
    if (exit_code != nullptr) *exit_code = -1;
    return out;
  }
  char buf[4096];
  size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int status = ::pclose(p);
  if (exit_code != nullptr) *exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return out;
}

}  // namespace swlio::test
