#include "swlio/drivers/imu_config.h"

#include <algorithm>
#include <array>

namespace swlio::drivers {

ConfigIssues ImuConfig::Validate() const {
  ConfigIssues issues;
  constexpr std::array<int64_t, 9> kBauds = {9600,   19200,  38400,  57600,  115200,
                                             230400, 460800, 921600, 2000000};
  CheckThat(issues, !device.empty(), "device", "must name a serial device");
  CheckThat(issues, std::find(kBauds.begin(), kBauds.end(), baud) != kBauds.end(), "baud",
            "must be one of 9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600, 2000000, "
            "got " +
                std::to_string(baud));
  CheckInRange<int64_t>(issues, "output_rate_hz", output_rate_hz, 1, 2000);
  CheckInRange<int64_t>(issues, "reply_timeout_ms", reply_timeout_ms, 10, 10000);
  CheckInRange<int64_t>(issues, "configure_retries", configure_retries, 1, 20);
  return issues;
}

}  // namespace swlio::drivers
