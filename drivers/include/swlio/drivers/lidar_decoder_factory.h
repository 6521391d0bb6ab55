#pragma once
/// @file
/// The packet decoder for a configured LiDAR model ("rs16", "helios16p", "vlp16").

#include <memory>

#include "swlio/drivers/lidar_config.h"
#include "swlio/drivers/lidar_decoder.h"

namespace swlio::drivers {

/// The decoder for `config.model` with the config's range limits, rpm and lens offset
/// (EffectiveLensOffsetM: the vendor's unless configured); nullptr for an unknown model
/// (LidarConfig::Validate rejects those first).
std::unique_ptr<LidarPacketDecoder> MakeLidarDecoder(const LidarConfig& config);

}  // namespace swlio::drivers
