// SpscQueue: bounded, counts what it drops, and hands elements across two threads in order.

#include "swlio/daemon/pipeline/spsc_queue.h"

#include <gtest/gtest.h>

#include <thread>

namespace swlio::daemon {
namespace {

TEST(SpscQueue, DropsAndCountsWhenFull) {
  SpscQueue<int> q("test", "producer", "consumer", 4);
  int pushed = 0;
  for (int i = 0; i < 100; ++i) pushed += q.Push(i) ? 1 : 0;
  const QueueCounters c = q.Counters();
  EXPECT_GE(pushed, 4);  // moodycamel may round the capacity up to its block size
  EXPECT_LT(pushed, 100);
  EXPECT_EQ(c.pushed, static_cast<uint64_t>(pushed));
  EXPECT_EQ(c.dropped, static_cast<uint64_t>(100 - pushed));
  EXPECT_EQ(c.high_water, static_cast<size_t>(pushed));
  EXPECT_EQ(c.name, "test");
  EXPECT_EQ(c.producer, "producer");
  EXPECT_EQ(c.consumer, "consumer");
  int v = -1;
  ASSERT_TRUE(q.Pop(&v));
  EXPECT_EQ(v, 0) << "first in, first out; the dropped ones are the newest";
}

TEST(SpscQueue, WaitPopTimesOutWhenEmpty) {
  SpscQueue<int> q("test", "a", "b", 8);
  int v = 0;
  EXPECT_FALSE(q.WaitPop(&v, 1000));
  EXPECT_FALSE(q.Pop(&v));
}

TEST(SpscQueue, CarriesEverythingAcrossThreadsInOrder) {
  SpscQueue<int64_t> q("test", "producer", "consumer", 64);
  constexpr int64_t kCount = 200'000;
  std::thread producer([&] {
    for (int64_t i = 0; i < kCount;) {
      if (q.Push(i)) ++i;  // the test's producer retries; the daemon's drop instead
    }
  });
  int64_t expected = 0;
  int64_t v = 0;
  while (expected < kCount) {
    if (!q.WaitPop(&v, 1'000'000)) break;
    ASSERT_EQ(v, expected);
    ++expected;
  }
  producer.join();
  EXPECT_EQ(expected, kCount);
  EXPECT_EQ(q.Counters().pushed, static_cast<uint64_t>(kCount));
}

}  // namespace
}  // namespace swlio::daemon
