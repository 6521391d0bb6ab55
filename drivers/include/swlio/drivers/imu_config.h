#pragma once
/// @file
/// Configuration of the Xsens MTi serial receiver (target: MTi-G-710).

#include <cstdint>
#include <string>

#include "swlio/core/config_issue.h"

namespace swlio::drivers {

struct ImuConfig {
  std::string device = "/dev/ttyUSB0";  ///< serial device (USB-serial of the MTi)
  /// Line rate. MTi 1-/100-series ports accept 9600 … 921600 and 2000000 where the USB-serial
  /// adapter allows; 400 Hz MTData2 output needs ≥ 460800.
  int64_t baud = 921600;
  /// Rate requested for the inertial items when configuring the device, Hz.
  int64_t output_rate_hz = 400;
  /// Send GoToConfig / SetOutputConfiguration / GoToMeasurement at start-up.
  bool configure_on_start = true;
  int64_t reply_timeout_ms = 500;  ///< wait for each acknowledgement
  int64_t configure_retries = 3;   ///< attempts per configuration message

  ConfigIssues Validate() const;
};

}  // namespace swlio::drivers
