// Doorbell: a consumer with several input queues wakes for whichever gets data first, and one
// wake-up serves every ring before it.

#include "swlio/daemon/pipeline/doorbell.h"

#include <gtest/gtest.h>

#include <thread>

#include "swlio/daemon/pipeline/spsc_queue.h"

namespace swlio::daemon {
namespace {

TEST(Doorbell, TimesOutWhenNotRung) {
  Doorbell bell;
  EXPECT_FALSE(bell.Wait(1000));
}

TEST(Doorbell, OneWaitClearsEveryRingBeforeIt) {
  Doorbell bell;
  for (int i = 0; i < 5; ++i) bell.Ring();
  EXPECT_TRUE(bell.Wait(0));
  EXPECT_FALSE(bell.Wait(1000)) << "the four later rings were served by the first wake-up";
}

TEST(Doorbell, QueuesRingTheirConsumersBell) {
  Doorbell bell;
  SpscQueue<int> a("a", "p", "c", 8);
  SpscQueue<int> b("b", "p", "c", 8);
  a.RingOnPush(&bell);
  b.RingOnPush(&bell);
  ASSERT_TRUE(b.Push(7));
  EXPECT_TRUE(bell.Wait(0));
  int v = 0;
  EXPECT_FALSE(a.Pop(&v));
  ASSERT_TRUE(b.Pop(&v));
  EXPECT_EQ(v, 7);
  EXPECT_FALSE(bell.Wait(1000));
}

TEST(Doorbell, ConsumerOfTwoQueuesGetsEverythingFromBoth) {
  Doorbell bell;
  SpscQueue<int> a("a", "pa", "c", 64);
  SpscQueue<int> b("b", "pb", "c", 64);
  a.RingOnPush(&bell);
  b.RingOnPush(&bell);
  constexpr int kCount = 50'000;
  auto produce = [](SpscQueue<int>* q) {
    for (int i = 0; i < kCount;) {
      if (q->Push(i)) ++i;  // the test's producers retry; the daemon's drop instead
    }
  };
  std::thread pa(produce, &a);
  std::thread pb(produce, &b);
  int next_a = 0, next_b = 0, v = 0;
  while (next_a < kCount || next_b < kCount) {
    // Only the bell sleeps: a lost ring would stall here for the full 2 s timeout and fail.
    ASSERT_TRUE(bell.Wait(2'000'000)) << "a: " << next_a << ", b: " << next_b;
    while (a.Pop(&v)) ASSERT_EQ(v, next_a++);
    while (b.Pop(&v)) ASSERT_EQ(v, next_b++);
  }
  pa.join();
  pb.join();
  EXPECT_EQ(next_a, kCount);
  EXPECT_EQ(next_b, kCount);
}

}  // namespace
}  // namespace swlio::daemon
