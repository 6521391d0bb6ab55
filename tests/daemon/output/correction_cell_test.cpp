// CorrectionCell (the publisher's current map correction for other threads) and the sweep
// publisher that reads it: nothing before the first correction (the sweep is held back and
// counted), the exact matrix after, and never a torn one while the writer keeps writing.
#include "swlio/daemon/output/correction_cell.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "swlio/daemon/output/sweep_publisher.h"

namespace swlio::daemon {
namespace {

Eigen::Isometry3d Pose(double x, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).matrix();
  T.translation() << x, -2.0 * x, 0.5;
  return T;
}

TEST(CorrectionCell, NothingBeforeTheFirstStoreThenTheExactMatrix) {
  CorrectionCell cell;
  Eigen::Isometry3d T = Pose(9.0, 0.0);
  EXPECT_FALSE(cell.Load(&T));
  EXPECT_TRUE(T.isApprox(Pose(9.0, 0.0)));  // untouched
  cell.Store(Pose(1.25, 0.3));
  ASSERT_TRUE(cell.Load(&T));
  EXPECT_EQ(T.matrix(), Pose(1.25, 0.3).matrix());
}

TEST(CorrectionCell, AReaderNeverSeesATornMatrix) {
  CorrectionCell cell;
  const Eigen::Isometry3d a = Pose(1.0, 0.1), b = Pose(-3.0, -0.7);
  cell.Store(a);
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    for (int i = 0; !stop; ++i) cell.Store(i % 2 == 0 ? b : a);
  });
  int torn = 0;
  for (int i = 0; i < 20'000; ++i) {
    Eigen::Isometry3d T;
    ASSERT_TRUE(cell.Load(&T));
    torn += T.matrix() == a.matrix() || T.matrix() == b.matrix() ? 0 : 1;
  }
  stop = true;
  writer.join();
  EXPECT_EQ(torn, 0);
}

TEST(SweepPublisher, HoldsSweepsBackUntilThereIsACorrection) {
  CorrectionCell cell;
  SweepPublisher sweeps(nullptr, "map");
  sweeps.CorrectWith(&cell);
  Scan scan;
  scan.points.resize(100);
  EXPECT_FALSE(sweeps.Publish(scan, Eigen::Isometry3d::Identity(), 1'000));
  EXPECT_EQ(sweeps.counters().held, 1u);
  EXPECT_EQ(sweeps.counters().published, 0u);
  cell.Store(Pose(2.0, 0.2));
  EXPECT_TRUE(sweeps.Publish(scan, Eigen::Isometry3d::Identity(), 2'000));
  EXPECT_EQ(sweeps.counters().published, 1u);
  EXPECT_EQ(sweeps.counters().failures, 0u);
}

}  // namespace
}  // namespace swlio::daemon
