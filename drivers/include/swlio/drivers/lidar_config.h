#pragma once
/// @file
/// Configuration of the LiDAR receiver (RS-LiDAR-16 by default; RS-Helios-16P and VLP-16 too).

#include <array>
#include <cstdint>
#include <limits>
#include <string>

#include "swlio/core/config_issue.h"

namespace swlio::drivers {

struct LidarConfig {
  /// Packet format: "rs16", "helios16p" or "vlp16".
  std::string model = "rs16";
  /// Local address the UDP sockets bind to ("0.0.0.0" on the robot; tests use 127.0.0.1).
  std::string bind_address = "0.0.0.0";
  uint16_t msop_port = 6699;   ///< data packets (RS16 factory default 6699)
  uint16_t difop_port = 7788;  ///< device-info packets (RS16 factory default 7788)
  /// Azimuth at which one sweep ends and the next begins, degrees in [0, 360).
  double cut_angle_deg = 0.0;
  double min_range_m = 0.4;    ///< returns closer than this are dropped (robot body)
  double max_range_m = 150.0;  ///< RS-LiDAR-16 datasheet range: 150 m
  /// Requested SO_RCVBUF; the granted size is reported at start-up.
  int64_t rcvbuf_bytes = int64_t{8} * 1024 * 1024;
  /// The receiving thread sleeps this long after each batch it took, so that one wake-up takes
  /// several datagrams (an RS16 sends one every 1.3 ms; each is stamped by the kernel on
  /// arrival, so the wait moves no time). 0: every datagram wakes it.
  int64_t rx_batch_ms = 5;
  /// Used until a DIFOP packet supplies the unit's own calibration (RS16 nominal: −15°…+15°
  /// in 2° steps, ring 0 lowest).
  std::array<double, 16> vertical_angles_deg = {-15, -13, -11, -9, -7, -5, -3, -1,
                                                1,   3,   5,   7,  9,  11, 13, 15};
  /// Motor speed assumed until DIFOP reports it (300, 600 or 1200 rpm).
  double rpm = 600.0;
  /// Distance of the optical centre from the rotation axis along the firing's azimuth, metres
  /// in [0, 0.1], for a unit whose vendor calibration differs. NaN (absent): the model's vendor
  /// value, VendorLensOffsetM(model).
  double lens_offset_m = std::numeric_limits<double>::quiet_NaN();

  /// The lens offset the decoder uses: lens_offset_m, or the model's vendor value when absent.
  double EffectiveLensOffsetM() const;
  ConfigIssues Validate() const;
};

/// The lens offset the vendor's own driver applies for `model`: rs16 0.03825 m, helios16p
/// 0.03498 m (rs_driver RX), vlp16 0 (velodyne); 0 for an unknown model.
double VendorLensOffsetM(const std::string& model);

}  // namespace swlio::drivers
