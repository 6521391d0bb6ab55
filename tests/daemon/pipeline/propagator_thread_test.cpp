// PropagatorThread: no IMU-rate pose without an optimized state; a reset from the optimizer
// (its estimator re-initialized after a divergence) stops the output until the next state; the
// imu_rx thread's serial bytes are decoded here, a re-open restarting the decoder in place.

#include "swlio/daemon/pipeline/propagator_thread.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <span>
#include <thread>
#include <vector>

#include "recording/sim_recording.h"

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

  /// The Xbus frame of a level sample `k` at 400 Hz with PacketCounter `counter`.
  static std::vector<uint8_t> FrameAt(int64_t k, uint16_t counter) {
    sim::SimImuSample sample;
    sample.sample_time_fine = static_cast<uint32_t>(1000 + k * 25);
    sample.packet_counter = counter;
    sample.acc_mps2 = Eigen::Vector3d(0.0, 0.0, 9.80665);
    std::vector<uint8_t> frame(256);
    frame.resize(sim::EncodeImuFrame(sample, frame));
    return frame;
  }

  void PushChunk(std::span<const uint8_t> bytes, int64_t t_rx_ns, uint32_t epoch) {
    SerialChunk chunk;
    std::copy(bytes.begin(), bytes.end(), chunk.bytes.begin());
    chunk.size = static_cast<uint16_t>(bytes.size());
    chunk.epoch = epoch;
    chunk.t_rx_ns = t_rx_ns;
    EXPECT_TRUE(serial_in_.Push(chunk));
  }

  /// Feeds `n` level samples at 400 Hz (SampleTimeFine in 10 kHz ticks), each as the Xbus
  /// frame of one serial read, and waits until the thread has handed all of them on; returns
  /// the IMU-rate poses it made meanwhile.
  size_t Feed(int n) {
    for (int i = 0; i < n; ++i, ++k_) {
      PushChunk(FrameAt(k_, static_cast<uint16_t>(k_)), 1'000'000'000 + k_ * 2'500'000, 1);
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

  SpscQueue<SerialChunk> serial_in_{"imu_serial", "test", "propagator", 1024};
  SpscQueue<SweepEstimate> states_{"states", "test", "propagator", 64};
  SpscQueue<ImuSample> imu_out_{"imu_samples", "propagator", "test", 1024};
  SpscQueue<ImuRatePose> poses_{"poses", "propagator", "test", 1024};
  PropagatorThread propagator_{921600, estimator::ImuRatePropagatorConfig{},
                               PropagatorQueues{&serial_in_, &states_, &imu_out_, &poses_}};
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

// The serial bytes are decoded on this thread: every read ends 20 bytes into the next frame,
// and the device is unplugged 20 bytes into frame 10 and comes back (epoch 2) with its
// PacketCounter elsewhere. Each sample takes the time of the read that completed its frame;
// the cut frame is skipped; the new stream is neither a gap nor a checksum error.
TEST_F(PropagatorThreadTest, DecodesFramesSplitAcrossReadsAndRestartsAtANewEpoch) {
  constexpr size_t kCarry = 20;
  const auto t_of = [](int64_t k) { return 1'000'000'000 + k * 2'500'000; };
  std::vector<uint8_t> frame = FrameAt(0, 0);
  PushChunk(std::span(frame).first(kCarry), t_of(0) - 1'000'000, 1);
  for (int64_t k = 0; k < 10; ++k) {
    std::vector<uint8_t> read(frame.begin() + kCarry, frame.end());
    frame = FrameAt(k + 1, static_cast<uint16_t>(k + 1));
    read.insert(read.end(), frame.begin(), frame.begin() + kCarry);
    PushChunk(read, t_of(k), 1);
  }
  for (int64_t k = 11; k < 20; ++k)
    PushChunk(FrameAt(k, static_cast<uint16_t>(289 + k)), t_of(k), 2);
  std::vector<int64_t> t_rx;
  ImuSample s;
  while (t_rx.size() < 19 && imu_out_.WaitPop(&s, 2'000'000)) t_rx.push_back(s.t_ns);
  ASSERT_EQ(t_rx.size(), 19u);
  PropagatorCounters c;
  for (int i = 0; i < 200 && (c = propagator_.counters()).decode.samples < 19; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(c.decode.samples, 19u);
  EXPECT_EQ(c.decode.restarts, 1u);
  EXPECT_EQ(c.decode.skipped_bytes, kCarry);
  EXPECT_EQ(c.decode.checksum_errors, 0u);
  EXPECT_EQ(c.decode.counter_gaps, 0u);
  EXPECT_EQ(c.decode.missing_packets, 0u);
  EXPECT_EQ(c.samples, 19u) << "all mapped to host time";
  for (size_t i = 1; i < t_rx.size(); ++i) {
    const int64_t dt = t_rx[i] - t_rx[i - 1];
    EXPECT_GT(dt, 0);
    EXPECT_LT(dt, 10'000'000) << "sample " << i;
  }
}

}  // namespace
}  // namespace swlio::daemon
