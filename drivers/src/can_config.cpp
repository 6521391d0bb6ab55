#include "swlio/drivers/can_config.h"

#include <net/if.h>

namespace swlio::drivers {

ConfigIssues CanConfig::Validate() const {
  ConfigIssues issues;
  CheckThat(issues, !interface.empty() && interface.size() < IFNAMSIZ, "interface",
            "must be an interface name of 1 to " + std::to_string(IFNAMSIZ - 1) + " characters");
  return issues;
}

}  // namespace swlio::drivers
