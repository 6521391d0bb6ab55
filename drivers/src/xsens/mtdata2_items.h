#pragma once
// Internal: the table of real-valued MTData2 items shared by the decoder and the encoder.
// Value counts per item from Xsens MT0101P, "Data identifiers" table.

#include <array>
#include <cstdint>
#include <optional>

#include "swlio/drivers/xsens/mtdata2.h"

namespace swlio::drivers::xsens::internal {

struct RealItemDef {
  uint16_t type;  ///< XDI & 0xFFF0
  uint8_t count;  ///< values per item
  std::optional<XsensReal> MtData2Sample::*field;
};

inline constexpr std::array<RealItemDef, 16> kRealItems = {{
    {xdi::kTemperature, 1, &MtData2Sample::temperature_degc},
    {xdi::kQuaternion, 4, &MtData2Sample::quaternion},
    {xdi::kRotationMatrix, 9, &MtData2Sample::rotation_matrix},
    {xdi::kEulerAngles, 3, &MtData2Sample::euler_deg},
    {xdi::kDeltaV, 3, &MtData2Sample::delta_v_mps},
    {xdi::kAcceleration, 3, &MtData2Sample::acc_mps2},
    {xdi::kFreeAcceleration, 3, &MtData2Sample::free_acc_mps2},
    {xdi::kAccelerationHr, 3, &MtData2Sample::acc_hr_mps2},
    {xdi::kAltitudeEllipsoid, 1, &MtData2Sample::altitude_ellipsoid_m},
    {xdi::kPositionEcef, 3, &MtData2Sample::position_ecef_m},
    {xdi::kLatLon, 2, &MtData2Sample::lat_lon_deg},
    {xdi::kRateOfTurn, 3, &MtData2Sample::rate_of_turn_radps},
    {xdi::kDeltaQ, 4, &MtData2Sample::delta_q},
    {xdi::kRateOfTurnHr, 3, &MtData2Sample::rate_of_turn_hr_radps},
    {xdi::kMagneticField, 3, &MtData2Sample::mag_au},
    {xdi::kVelocityXyz, 3, &MtData2Sample::velocity_mps},
}};

inline const RealItemDef* FindRealItem(uint16_t type) {
  for (const RealItemDef& def : kRealItems) {
    if (def.type == type) return &def;
  }
  return nullptr;
}

/// Full XDI of a real item: type | frame bits | precision bits.
inline uint16_t RealXdi(uint16_t type, const XsensReal& r) {
  return static_cast<uint16_t>(type | (static_cast<uint16_t>(r.frame) << 2) |
                               static_cast<uint16_t>(r.precision));
}

}  // namespace swlio::drivers::xsens::internal
