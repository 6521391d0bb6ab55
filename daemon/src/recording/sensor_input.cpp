#include "swlio/daemon/recording/sensor_input.h"

namespace swlio::daemon {

int64_t RecordingEvent::t_ns() const {
  switch (kind) {
    case Kind::kImu:
      return imu.t_ns;
    case Kind::kScan:
      return scan.t_start_ns;
    case Kind::kGnss:
      return gnss.t_ns;
    case Kind::kWheel:
      return wheel.t_ns;
  }
  return 0;
}

}  // namespace swlio::daemon
