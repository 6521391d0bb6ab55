#include "swlio/drivers/lidar_decoder_factory.h"

#include "swlio/drivers/helios16p_decoder.h"
#include "swlio/drivers/rs16_decoder.h"
#include "swlio/drivers/vlp16_decoder.h"

namespace swlio::drivers {

std::unique_ptr<LidarPacketDecoder> MakeLidarDecoder(const LidarConfig& config) {
  const double lens_offset_m = config.EffectiveLensOffsetM();
  if (config.model == "rs16") {
    Rs16DecoderOptions o;
    o.lens_offset_m = lens_offset_m;
    return std::make_unique<Rs16Decoder>(config, o);
  }
  if (config.model == "helios16p") {
    Helios16pOptions o;
    o.min_range_m = config.min_range_m;
    o.max_range_m = config.max_range_m;
    o.rpm = config.rpm;
    o.lens_offset_m = lens_offset_m;
    return std::make_unique<Helios16pDecoder>(o);
  }
  if (config.model == "vlp16") {
    Vlp16Options o;
    o.min_range_m = config.min_range_m;
    o.max_range_m = config.max_range_m;
    o.rpm = config.rpm;
    o.lens_offset_m = lens_offset_m;
    return std::make_unique<Vlp16Decoder>(o);
  }
  return nullptr;
}

}  // namespace swlio::drivers
