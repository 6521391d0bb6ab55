#include "swlio/drivers/lidar_config.h"

#include <algorithm>
#include <cmath>

#include "swlio/drivers/helios16p_decoder.h"
#include "swlio/drivers/rs16_protocol.h"

namespace swlio::drivers {

double VendorLensOffsetM(const std::string& model) {
  if (model == "rs16") return rs16::kLensRxM;
  if (model == "helios16p") return helios16p::kLensRxM;
  return 0.0;
}

double LidarConfig::EffectiveLensOffsetM() const {
  return std::isnan(lens_offset_m) ? VendorLensOffsetM(model) : lens_offset_m;
}

ConfigIssues LidarConfig::Validate() const {
  ConfigIssues issues;
  CheckThat(issues, model == "rs16" || model == "helios16p" || model == "vlp16", "model",
            "must be one of rs16, helios16p, vlp16, got '" + model + "'");
  CheckThat(issues, !bind_address.empty(), "bind_address", "must not be empty");
  CheckThat(issues, msop_port != 0, "msop_port", "must be a UDP port in [1, 65535]");
  CheckThat(issues, difop_port != 0, "difop_port", "must be a UDP port in [1, 65535]");
  CheckThat(issues, msop_port != difop_port, "difop_port", "must differ from msop_port");
  CheckInRange(issues, "cut_angle_deg", cut_angle_deg, 0.0, 359.999);
  CheckInRange(issues, "min_range_m", min_range_m, 0.0, 10.0);
  CheckInRange(issues, "max_range_m", max_range_m, 1.0, 300.0);
  CheckThat(issues, min_range_m < max_range_m, "max_range_m", "must exceed min_range_m");
  CheckInRange<int64_t>(issues, "rcvbuf_bytes", rcvbuf_bytes, 65536, int64_t{1} << 30);
  CheckInRange<int64_t>(issues, "rx_batch_ms", rx_batch_ms, 0, 50);
  const bool angles_ok = std::all_of(vertical_angles_deg.begin(), vertical_angles_deg.end(),
                                     [](double a) { return a >= -90.0 && a <= 90.0; });
  CheckThat(issues, angles_ok, "vertical_angles_deg", "every angle must be in [-90, 90]");
  if (!std::isnan(lens_offset_m)) CheckInRange(issues, "lens_offset_m", lens_offset_m, 0.0, 0.1);
  CheckThat(issues, rpm == 300.0 || rpm == 600.0 || rpm == 1200.0, "rpm",
            "must be 300, 600 or 1200");
  return issues;
}

}  // namespace swlio::drivers
