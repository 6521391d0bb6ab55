#include "swlio/daemon/pipeline/time_scale.h"

#include <gtest/gtest.h>

namespace swlio::daemon {
namespace {

TEST(TimeScale, IdentityAtOneAndRoundTripOtherwise) {
  const TimeScale one{1'000'000'000, 1.0};
  EXPECT_EQ(one.ToDaemon(5'123'456'789), 5'123'456'789);
  const TimeScale two{1'000'000'000, 2.0};
  EXPECT_EQ(two.ToDaemon(1'000'000'000), 1'000'000'000);
  EXPECT_EQ(two.ToDaemon(1'500'000'000), 2'000'000'000);  // 0.5 s of host = 1 s of sensor
  EXPECT_EQ(two.ToHost(two.ToDaemon(7'777'777'777)), 7'777'777'777);
}

}  // namespace
}  // namespace swlio::daemon
