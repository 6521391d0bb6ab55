#pragma once
/// @file
/// One classic CAN 2.0 frame, independent of the socket API (SocketCAN's `struct can_frame`
/// is converted to and from this in the reader; candump logs parse into it).
///
/// CAN 2.0A/B (ISO 11898-1): 11-bit standard or 29-bit extended identifier, data length
/// code 0–8, up to 8 data bytes; a remote frame carries a DLC but no data. CAN FD frames
/// (up to 64 bytes) are not represented: the readers count and drop them.

#include <array>
#include <cstdint>

namespace swlio::drivers {

inline constexpr uint32_t kCanMaxStandardId = 0x7FF;
inline constexpr uint32_t kCanMaxExtendedId = 0x1FFFFFFF;

struct CanFrame {
  uint32_t id = 0;                ///< identifier without flags (11 or 29 bits)
  bool extended = false;          ///< 29-bit identifier
  bool remote = false;            ///< remote transmission request (no data)
  bool error = false;             ///< SocketCAN error frame (id holds the error class)
  uint8_t dlc = 0;                ///< data length, 0–8
  std::array<uint8_t, 8> data{};  ///< bytes past `dlc` are zero
};

}  // namespace swlio::drivers
