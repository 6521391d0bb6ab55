#include "swlio/estimator/common/replace_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace swlio::estimator {
namespace {

std::string ErrnoMessage() { return std::error_code(errno, std::generic_category()).message(); }

// Flushes a file (or directory) to the disk: a rename must not land before the data does.
bool SyncPath(const std::string& path, bool directory) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | (directory ? O_DIRECTORY : 0));
  if (fd < 0) return false;
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  return ok;
}

// The content into `tmp`, flushed to the disk; false with `*why` set where a step failed.
bool WriteTemporary(const std::string& tmp,
                    const std::string& what,
                    const std::function<bool(std::ostream&, std::string*)>& write,
                    std::string* why) {
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      *why = what + ": cannot create " + tmp + ": " + ErrnoMessage();
      return false;
    }
    if (!write(out, why)) return false;
    out.close();
    if (!out) {
      *why = what + ": closing " + tmp + " failed: " + ErrnoMessage();
      return false;
    }
  }
  if (!SyncPath(tmp, false)) {
    *why = what + ": flushing " + tmp + " to disk failed: " + ErrnoMessage();
    return false;
  }
  return true;
}

}  // namespace

bool ReplaceFile(const std::string& path,
                 const std::string& what,
                 const std::function<bool(std::ostream& out, std::string* why)>& write,
                 std::string* error) {
  const std::string tmp = path + ".tmp";
  std::string why;
  std::error_code ec;
  bool ok = WriteTemporary(tmp, what, write, &why);
  if (ok) {
    std::filesystem::rename(tmp, path, ec);
    if (ec) why = what + ": renaming " + tmp + " to " + path + " failed: " + ec.message();
    ok = !ec;
  }
  if (!ok) {
    std::filesystem::remove(tmp, ec);
    if (error != nullptr) *error = why;
    return false;
  }
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  SyncPath(dir.empty() ? "." : dir.string(), true);
  return true;
}

}  // namespace swlio::estimator
