// The simulator's setup options (sim_setup.h): a longer standing start (an inspection stop
// before driving off) keeps the route and only delays it.

#include "scenarios/sim_setup.h"

#include <gtest/gtest.h>

namespace swlio::sim {
namespace {

TEST(SimSetup, StandStartDelaysTheSameRoute) {
  auto usual = MakeSimSetup("short", 1);
  auto stop = MakeSimSetup("short", 1, std::nullopt, std::nullopt, 30.0);
  ASSERT_TRUE(usual && stop);
  EXPECT_NEAR(stop->trajectory->duration_s() - usual->trajectory->duration_s(), 28.0, 1e-9);
  const Kinematics start = stop->trajectory->At(0.0);
  const Kinematics still = stop->trajectory->At(29.99);
  EXPECT_LT((still.p_world - start.p_world).norm(), 1e-9);
  EXPECT_LT(still.v_world.norm(), 1e-9);
  // After the stand, the same drive: 10 s into it both are at the same place.
  EXPECT_LT((stop->trajectory->At(40.0).p_world - usual->trajectory->At(12.0).p_world).norm(),
            1e-9);
  EXPECT_GT((stop->trajectory->At(40.0).p_world - start.p_world).norm(), 1.0);
}

}  // namespace
}  // namespace swlio::sim
