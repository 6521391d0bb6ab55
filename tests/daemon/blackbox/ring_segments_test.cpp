// The ring's bounds (ring_segments.h): by span only what no incident still needs, by bytes
// anything, oldest first; numbering continues after an earlier run's folders.

#include "swlio/daemon/blackbox/ring_segments.h"

#include <gtest/gtest.h>

#include <fstream>

#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr int64_t kSec = 1'000'000'000;

/// A segment folder with one file of `bytes`, spanning [start_s, start_s + 10).
SegmentInfo Segment(RingSegments* ring, int64_t start_s, uint64_t bytes) {
  SegmentInfo s;
  s.dir = ring->NextDir();
  std::filesystem::create_directories(s.dir);
  std::ofstream(s.dir / "lidar.pcap") << std::string(bytes, 'x');
  s.start_ns = start_s * kSec;
  s.end_ns = (start_s + 10) * kSec;
  s.bytes = DirectoryBytes(s.dir);
  return s;
}

TEST(RingSegments, SpanTrimsOnlyWhatNoIncidentNeedsAndBytesTrimAnything) {
  const auto dir = test::MakeTempDir("ring_segments");
  RingSegments ring(dir);
  for (int64_t t = 0; t < 60; t += 10) ring.Add(Segment(&ring, t, 1000));
  EXPECT_EQ(ring.count(), 6u);
  EXPECT_EQ(ring.bytes(), 6000u);
  // Span 30 s at t = 60: segments starting before 30 s go, but an incident needs 15 s on.
  const RingBounds bounds{30 * kSec, 1'000'000};
  EXPECT_EQ(ring.Trim(60 * kSec, bounds, 0, 15 * kSec), 1u);  // [0, 10) only
  EXPECT_EQ(ring.oldest_start_ns(), 10 * kSec);
  EXPECT_EQ(ring.Trim(60 * kSec, bounds, 0, INT64_MAX), 2u);  // [10, 20), [20, 30)
  EXPECT_EQ(ring.count(), 3u);
  // Bytes: 3000 closed + 1500 open over 4000: the oldest goes even if an incident needs it.
  EXPECT_EQ(ring.Trim(60 * kSec, {3600 * kSec, 4000}, 1500, 0), 1u);
  EXPECT_EQ(ring.count(), 2u);
  EXPECT_FALSE(std::filesystem::exists(dir / "seg-000003"));
  EXPECT_TRUE(std::filesystem::exists(dir / "seg-000004"));
  EXPECT_EQ(ring.deleted(), 4u);
  const std::vector<SegmentInfo> mid = ring.Overlapping(45 * kSec, 48 * kSec);
  ASSERT_EQ(mid.size(), 1u);
  EXPECT_EQ(mid[0].start_ns, 40 * kSec);
}

TEST(RingSegments, NumbersContinueAfterAnEarlierRunsFolders) {
  const auto dir = test::MakeTempDir("ring_leftovers");
  std::filesystem::create_directories(dir / "seg-000007");
  std::filesystem::create_directories(dir / "seg-000002");
  std::filesystem::create_directories(dir / "seg-x");  // not a segment
  std::ofstream(dir / "seg-000009") << "a file, not a folder";
  RingSegments ring(dir);
  const std::vector<std::filesystem::path> left = ring.Leftovers();
  ASSERT_EQ(left.size(), 2u);
  EXPECT_EQ(left[0].filename(), "seg-000002");
  EXPECT_EQ(left[1].filename(), "seg-000007");
  EXPECT_EQ(ring.NextDir().filename(), "seg-000008");
}

}  // namespace
}  // namespace swlio::daemon
