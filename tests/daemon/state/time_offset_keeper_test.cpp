// When swliod keeps its time offset: a start begins from the saved estimate where the offset is
// estimated online, and only there; gated estimates that say something new are written, at most
// once a period while running and always at stop.

#include "swlio/daemon/state/time_offset_keeper.h"

#include <gtest/gtest.h>

#include <fstream>

#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr int64_t kPeriodNs = 60'000'000'000;

estimator::TimeOffsetStatus Gated(double estimate_s, double sigma_s, size_t updates = 5) {
  estimator::TimeOffsetStatus s;
  s.enabled = true;
  s.gated = true;
  s.offset_s = s.estimate_s = estimate_s;
  s.sigma_s = sigma_s;
  s.updates = updates;
  return s;
}

std::filesystem::path Saved(const std::string& tag, double offset_s) {
  const auto path = test::MakeTempDir(tag) / "time_offset.yaml";
  SavedTimeOffset s;
  s.offset_s = offset_s;
  s.sigma_s = 1e-4;
  s.updates = 40;
  std::string error;
  EXPECT_TRUE(WriteTimeOffsetState(path, s, &error)) << error;
  return path;
}

TEST(TimeOffsetKeeper, AStartBeginsFromTheSavedEstimate) {
  TimeOffsetKeeper keeper(Saved("keeper_start", -0.0102).string(), kPeriodNs);
  estimator::TimeOffsetConfig c;
  keeper.Apply(&c);
  EXPECT_DOUBLE_EQ(c.initial_offset_s, -0.0102);
  ASSERT_TRUE(keeper.saved());
  EXPECT_EQ(keeper.saved()->updates, 40u);
  EXPECT_TRUE(c.Validate().empty());
}

TEST(TimeOffsetKeeper, AFixedCalibrationAWrongFileOrNoFileLeaveTheConfiguredStart) {
  const auto path = Saved("keeper_fixed", -0.0102);
  estimator::TimeOffsetConfig fixed;
  fixed.estimate = false;
  fixed.initial_offset_s = 0.003;
  TimeOffsetKeeper keeper(path.string(), kPeriodNs);
  keeper.Apply(&fixed);
  EXPECT_DOUBLE_EQ(fixed.initial_offset_s, 0.003);
  keeper.Flush(Gated(0.003, 1e-4));  // not estimated: nothing is written either
  EXPECT_EQ(keeper.writes(), 0u);

  estimator::TimeOffsetConfig narrow;  // the file's offset beyond max_offset_s
  narrow.max_offset_s = 0.005;
  TimeOffsetKeeper beyond(path.string(), kPeriodNs);
  beyond.Apply(&narrow);
  EXPECT_DOUBLE_EQ(narrow.initial_offset_s, 0.0);

  std::ofstream(path) << "format: swlio-time-offset 1\noffset_s: -0.01\n";  // no sigma_s
  estimator::TimeOffsetConfig c;
  TimeOffsetKeeper malformed(path.string(), kPeriodNs);
  malformed.Apply(&c);
  EXPECT_DOUBLE_EQ(c.initial_offset_s, 0.0);
  EXPECT_FALSE(malformed.saved());
  malformed.Flush(Gated(-0.0101, 2e-4));  // and it is replaced once estimated
  EXPECT_EQ(malformed.writes(), 1u);
  std::string error;
  EXPECT_DOUBLE_EQ(ReadTimeOffsetState(path, &error)->offset_s, -0.0101) << error;

  TimeOffsetKeeper absent((path.parent_path() / "absent.yaml").string(), kPeriodNs);
  estimator::TimeOffsetConfig d;
  absent.Apply(&d);
  EXPECT_DOUBLE_EQ(d.initial_offset_s, 0.0);

  TimeOffsetKeeper off("", kPeriodNs);
  off.Apply(&d);
  off.Flush(Gated(-0.01, 1e-4));
  EXPECT_EQ(off.writes(), 0u);
}

TEST(TimeOffsetKeeper, GatedNewsIsWrittenOncePerPeriodAndAtStop) {
  const auto path = test::MakeTempDir("keeper_write") / "time_offset.yaml";
  TimeOffsetKeeper keeper(path.string(), kPeriodNs);
  estimator::TimeOffsetConfig c;
  keeper.Apply(&c);
  estimator::TimeOffsetStatus before_gate = Gated(-0.004, 3e-3, 0);
  before_gate.gated = false;
  keeper.Observe(before_gate, 1'000'000'000);
  EXPECT_FALSE(std::filesystem::exists(path));  // nothing known yet

  keeper.Observe(Gated(-0.0093, 4e-4), 9'000'000'000);  // the first gated estimate
  EXPECT_EQ(keeper.writes(), 1u);
  std::string error;
  EXPECT_DOUBLE_EQ(ReadTimeOffsetState(path, &error)->offset_s, -0.0093) << error;

  keeper.Observe(Gated(-0.0099, 3e-4), 20'000'000'000);  // news, but within the period
  EXPECT_EQ(keeper.writes(), 1u);
  keeper.Observe(Gated(-0.0099, 3e-4), 70'000'000'000);  // the period is over
  EXPECT_EQ(keeper.writes(), 2u);
  keeper.Observe(Gated(-0.0092, 2.9e-4), 200'000'000'000);  // no news: within 3σ, no narrower
  EXPECT_EQ(keeper.writes(), 2u);
  keeper.Observe(Gated(-0.0099, 2e-4), 260'000'000'000);  // σ narrowed by a third
  EXPECT_EQ(keeper.writes(), 3u);

  keeper.Observe(Gated(-0.0103, 1e-4), 270'000'000'000);
  EXPECT_EQ(keeper.writes(), 3u);
  keeper.Flush(Gated(-0.0103, 1e-4));  // at stop, whatever the period
  EXPECT_EQ(keeper.writes(), 4u);
  const auto read = ReadTimeOffsetState(path, &error);
  ASSERT_TRUE(read) << error;
  EXPECT_DOUBLE_EQ(read->offset_s, -0.0103);
  EXPECT_DOUBLE_EQ(read->sigma_s, 1e-4);
  EXPECT_EQ(read->saved_utc.size(), 20u);  // 2026-12-06T07:12:30Z

  // The next start begins there; its first, wider estimate nearby leaves the file alone, one
  // far outside both σ (the IMU's filter changed) replaces it.
  TimeOffsetKeeper restart(path.string(), kPeriodNs);
  estimator::TimeOffsetConfig from_file;
  restart.Apply(&from_file);
  restart.Observe(Gated(-0.0098, 3e-4), 9'000'000'000);
  EXPECT_EQ(restart.writes(), 0u);
  restart.Flush(Gated(-0.0061, 3e-4));
  EXPECT_EQ(restart.writes(), 1u);
  restart.Flush(Gated(-0.0103, 1e-4));  // written last: the file as it was
  EXPECT_EQ(restart.writes(), 2u);
  TimeOffsetKeeper next(path.string(), kPeriodNs);
  estimator::TimeOffsetConfig again;
  next.Apply(&again);
  EXPECT_DOUBLE_EQ(again.initial_offset_s, -0.0103);
}

TEST(TimeOffsetKeeper, AFailedWriteIsNoFailureOfTheDaemon) {
  const auto dir = test::MakeTempDir("keeper_fail");
  TimeOffsetKeeper keeper((dir / "missing" / "time_offset.yaml").string(), kPeriodNs);
  estimator::TimeOffsetConfig c;
  keeper.Apply(&c);
  keeper.Observe(Gated(-0.01, 1e-4), 9'000'000'000);
  keeper.Flush(Gated(-0.01, 1e-4));
  EXPECT_EQ(keeper.writes(), 0u);
  EXPECT_FALSE(keeper.saved());
}

}  // namespace
}  // namespace swlio::daemon
