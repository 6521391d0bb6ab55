// LabelledScanSource sweeps: every point inside its sweep's time span, in time order, and no
// firing twice. The sweep starting at a whole second follows a DIFOP packet (one a second).

#include "sensors/labelled_scan.h"

#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "scenarios/sim_setup.h"

namespace swlio::sim {
namespace {

TEST(LabelledScan, SweepAfterDifopHasEachFiringOnceAndInTime) {
  auto setup = MakeSimSetup("short", 1, 2.5);
  ASSERT_TRUE(setup.has_value());
  LidarSimulator lidar(setup->world.get(), setup->trajectory.get(), setup->lidar, 1);
  SimPacket packet;
  std::vector<SimReturn> returns;
  int difops = 0;
  while (lidar.Next(&packet, &returns)) {  // DIFOP at 0, 1 and 2 s: no returns with them
    if (packet.dst_port != setup->lidar.difop_port) continue;
    ++difops;
    EXPECT_TRUE(returns.empty()) << "DIFOP " << difops << " carries the last MSOP's returns";
  }
  EXPECT_EQ(difops, 3);

  LabelledScanSource source(*setup);
  LabelledScan ls;
  for (double t_s : {1.0, 2.0}) {
    ASSERT_TRUE(source.Next(&ls, t_s));
    ASSERT_FALSE(ls.scan.points.empty());
    std::set<std::pair<int64_t, uint16_t>> firings;  // (time, ring)
    int64_t last_dt_ns = 0;
    for (const LidarPoint& p : ls.scan.points) {
      EXPECT_GE(p.dt_ns, last_dt_ns) << "out of time order at t = " << t_s;
      EXPECT_LE(ls.scan.t_start_ns + p.dt_ns, ls.scan.t_end_ns);
      last_dt_ns = p.dt_ns;
      EXPECT_TRUE(firings.insert({p.dt_ns, p.ring}).second) << "firing twice at t = " << t_s;
    }
  }
}

}  // namespace
}  // namespace swlio::sim
