#include "swlio/daemon/runtime/version.h"

#include "swlio/version.h"

namespace swlio::daemon {

std::string SwlioVersion() {
  const std::string git = SWLIO_GIT_DESCRIBE;
  return std::string(SWLIO_VERSION) + (git.empty() ? "" : " (git " + git + ")");
}

}  // namespace swlio::daemon
