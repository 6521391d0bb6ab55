// PropagatorThread: no IMU-rate pose without an optimized state; a reset from the optimizer
// (its estimator re-initialized after a divergence) stops the output until the next state.

#include "swlio/daemon/pipeline/propagator_thread.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace swlio::daemon {
namespace {

class PropagatorThreadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    thread_ = std::thread([this] { propagator_.Run(stop_, Watchdog::Handle{}); });
  }
  void TearDown() override {
    stop_ = true;
    thread_.join();
  }

  /// Feeds `n` level samples at 400 Hz (SampleTimeFine in 10 kHz ticks) and waits until the
  /// thread has handed all of them on; returns the IMU-rate poses it made meanwhile.
  size_t Feed(int n) {
    for (int i = 0; i < n; ++i, ++k_) {
      ImuRaw r;
      r.t_rx_ns = 1'000'000'000 + k_ * 2'500'000;
      r.sample_time_fine = static_cast<uint32_t>(1000 + k_ * 25);
      r.has_sample_time_fine = true;
      r.has_inertial = true;
      r.frame_bytes = 47;
      r.acc_mps2 = Eigen::Vector3d(0.0, 0.0, 9.80665);
      EXPECT_TRUE(imu_in_.Push(r));
    }
    ImuSample s;
    for (int got = 0; got < n;) {
      if (imu_out_.WaitPop(&s, 2'000'000)) {
        newest_t_ns_ = s.t_ns;
        ++got;
      } else {
        ADD_FAILURE() << "the propagator handed on " << got << " of " << n << " samples";
        break;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // its last pose, if any
    size_t made = 0;
    ImuRatePose pose;
    while (poses_.Pop(&pose)) ++made;
    return made;
  }

  /// Sends an estimate and gives the thread time to apply it (it does so before its next
  /// sample, and at least every 50 ms while idle).
  void Send(const SweepEstimate& e) {
    ASSERT_TRUE(states_.Push(e));
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }

  SweepEstimate StateAtNewestSample() const {
    SweepEstimate e;
    e.status = estimator::OdometryStatus::kTracking;
    e.state.t_ns = newest_t_ns_;
    return e;
  }

  SpscQueue<ImuRaw> imu_in_{"imu_raw", "test", "propagator", 1024};
  SpscQueue<SweepEstimate> states_{"states", "test", "propagator", 64};
  SpscQueue<ImuSample> imu_out_{"imu_samples", "propagator", "test", 1024};
  SpscQueue<ImuRatePose> poses_{"poses", "propagator", "test", 1024};
  PropagatorThread propagator_{921600, estimator::ImuRatePropagatorConfig{},
                               PropagatorQueues{&imu_in_, &states_, &imu_out_, &poses_}};
  std::atomic<bool> stop_{false};
  std::thread thread_;
  int64_t k_ = 0;
  int64_t newest_t_ns_ = 0;
};

TEST_F(PropagatorThreadTest, AResetStopsTheOutputUntilTheNextState) {
  EXPECT_EQ(Feed(40), 0u) << "no optimized state yet";
  Send(StateAtNewestSample());
  EXPECT_GE(Feed(40), 40u);
  SweepEstimate reset;
  reset.reset = true;
  Send(reset);
  EXPECT_EQ(Feed(40), 0u) << "nothing propagated from the state before the reset";
  Send(StateAtNewestSample());
  EXPECT_GE(Feed(40), 40u) << "the next state starts the output again";
}

}  // namespace
}  // namespace swlio::daemon
