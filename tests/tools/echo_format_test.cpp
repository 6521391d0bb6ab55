// swlio-echo's latency CSV: a stamp's age is taken on the clock the stamp is on, CLOCK_REALTIME
// (swliod's default, ipc.stamp_clock) or CLOCK_MONOTONIC.

#include "echo_format.h"

#include <gtest/gtest.h>

#include <string>

namespace swlio::tools::echo {
namespace {

constexpr int64_t kSec = 1'000'000'000;

ipc::Received<ipc::PoseWithCovarianceStamped> Taken(int64_t stamp_ns) {
  ipc::Received<ipc::PoseWithCovarianceStamped> r;
  r.msg.t_ns = stamp_ns;
  r.receive_steady_ns = 3600 * kSec;                       // an hour after boot
  r.receive_realtime_ns = 1'780'000'000 * kSec + 250'000;  // 2026
  r.source_realtime_ns = r.receive_realtime_ns - 100'000;
  return r;
}

TEST(EchoFormat, AStampsAgeIsTakenOnItsOwnClock) {
  EXPECT_EQ(StampAgeNs(Taken(3600 * kSec - 4'000'000)), 4'000'000) << "monotonic stamp";
  EXPECT_EQ(StampAgeNs(Taken(1'780'000'000 * kSec - 3'750'000)), 4'000'000) << "realtime stamp";
  EXPECT_EQ(StampAgeNs(Taken(1'780'000'010 * kSec)), -10 * kSec + 250'000)
      << "a stamp 10 s ahead (a stepped wall clock) shows as negative age";
  EXPECT_EQ(LatencyRow(ipc::Topic::kPose, Taken(1'780'000'000 * kSec)),
            "pose,1780000000000000000,1780000000000150000,1780000000000250000,3600000000000,"
            "100000,250000");
}

}  // namespace
}  // namespace swlio::tools::echo
