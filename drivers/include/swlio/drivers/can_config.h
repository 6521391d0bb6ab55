#pragma once
/// @file
/// Configuration of the optional chassis wheel-odometry input over SocketCAN: the interface
/// and the layout of the odometry signals inside the chassis' CAN frames.
///
/// Signal layout follows the DBC conventions (Vector "DBC File Format Documentation" 1.0.1,
/// section 8.1): a signal is `length_bits` long; for Intel (little-endian) byte order
/// `start_bit` is the position of its least significant bit, for Motorola (big-endian) the
/// position of its most significant bit; bit n is bit (n % 8) of data byte (n / 8), LSB = 0.
/// `byte_offset` is a shorthand for byte-aligned fields: the field starts at that byte
/// (Intel: start_bit = 8·b, Motorola: start_bit = 8·b + 7).

#include <cstdint>
#include <string>
#include <vector>

#include "swlio/core/config_issue.h"

namespace swlio::drivers {

/// Where one physical value sits in a CAN frame: physical = raw · scale + offset.
struct CanSignalConfig {
  /// Which value this is: left_wheel_speed | right_wheel_speed (mode wheel_speeds),
  /// linear_velocity (m/s) | angular_velocity (rad/s, yaw rate, CCW positive) (mode twist).
  std::string role;
  int64_t can_id = -1;       ///< identifier without flags: ≤ 0x7FF, or ≤ 0x1FFFFFFF if extended
  bool extended = false;     ///< 29-bit identifier (CAN 2.0B)
  int64_t start_bit = -1;    ///< DBC start bit (see file comment); -1 = use byte_offset
  int64_t byte_offset = -1;  ///< byte-aligned alternative to start_bit; -1 = unset
  int64_t length_bits = 16;  ///< 1 to 64
  std::string byte_order = "intel";  ///< intel (little-endian) | motorola (big-endian)
  bool is_signed = true;             ///< two's complement raw value
  double scale = 1.0;                ///< physical units per LSB; negative flips a mirrored wheel
  double offset = 0.0;               ///< physical units added after scaling
  int64_t dlc = 0;                   ///< required data length of the frame; 0 = any that holds it

  ConfigIssues Validate() const;
};

struct CanConfig {
  bool enabled = false;            ///< off unless the chassis publishes odometry on CAN
  std::string interface = "can0";  ///< SocketCAN interface name

  /// wheel_speeds: left_wheel_speed + right_wheel_speed signals (differential drive);
  /// twist: linear_velocity + angular_velocity signals.
  std::string mode = "wheel_speeds";
  std::string wheel_speed_unit = "mps";  ///< mps (wheel rim speed) | radps (wheel rotation)
  double wheel_radius_m = 0.1;           ///< used when wheel_speed_unit is radps
  double track_width_m = 0.5;            ///< distance between the left and right wheels
  /// Signals in different frames are paired into one sample only when their receive times
  /// differ by at most this much; an older unpaired value is dropped (and counted).
  double max_pair_skew_s = 0.05;
  std::vector<CanSignalConfig> signals;

  /// Interface name; when `enabled`, a complete layout (see ValidateLayout()).
  ConfigIssues Validate() const;
  /// The layout alone: every signal valid, exactly the two roles of `mode`, positive geometry.
  ConfigIssues ValidateLayout() const;
};

}  // namespace swlio::drivers
