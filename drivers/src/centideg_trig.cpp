#include "swlio/drivers/detail/centideg_trig.h"

#include <cmath>
#include <numbers>

namespace swlio::drivers::detail {

CentidegTrig::CentidegTrig() {
  for (int32_t i = 0; i < kSteps; ++i) {
    const double rad = static_cast<double>(i) * 0.01 * std::numbers::pi / 180.0;
    sin_[static_cast<size_t>(i)] = static_cast<float>(std::sin(rad));
    cos_[static_cast<size_t>(i)] = static_cast<float>(std::cos(rad));
  }
}

const CentidegTrig& CentidegTrig::Get() {
  static const CentidegTrig table;
  return table;
}

}  // namespace swlio::drivers::detail
