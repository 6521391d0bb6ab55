#pragma once
/// @file
/// Configuration of the optional chassis wheel-odometry input over SocketCAN.

#include <string>

#include "swlio/core/config_issue.h"

namespace swlio::drivers {

struct CanConfig {
  bool enabled = false;            ///< off unless the chassis publishes odometry on CAN
  std::string interface = "can0";  ///< SocketCAN interface name

  ConfigIssues Validate() const;
};

}  // namespace swlio::drivers
