// The file that keeps the time offset across restarts: what is written reads back the same,
// and every malformed file is refused with the key and the reason, never taken half.

#include "swlio/daemon/state/time_offset_state.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "test_data.h"

namespace swlio::daemon {
namespace {

using ::testing::HasSubstr;

SavedTimeOffset Example() {
  SavedTimeOffset s;
  s.offset_s = -0.0103412;
  s.sigma_s = 8.62e-5;
  s.updates = 1843;
  s.saved_utc = "2026-12-06T07:12:30Z";
  return s;
}

std::string ParseError(const std::string& text) {
  std::string error;
  EXPECT_FALSE(ParseTimeOffsetState(text, &error)) << text;
  return error;
}

TEST(TimeOffsetState, WhatIsWrittenReadsBackTheSame) {
  const auto dir = test::MakeTempDir("time_offset_state");
  const auto path = dir / "time_offset.yaml";
  std::string error;
  ASSERT_TRUE(WriteTimeOffsetState(path, Example(), &error)) << error;
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".tmp"));
  const auto read = ReadTimeOffsetState(path, &error);
  ASSERT_TRUE(read) << error;
  EXPECT_DOUBLE_EQ(read->offset_s, -0.0103412);
  EXPECT_DOUBLE_EQ(read->sigma_s, 8.62e-5);
  EXPECT_EQ(read->updates, 1843u);
  EXPECT_EQ(read->saved_utc, "2026-12-06T07:12:30Z");
  // A second write replaces the first whole.
  SavedTimeOffset later = Example();
  later.offset_s = 0.004;
  ASSERT_TRUE(WriteTimeOffsetState(path, later, &error)) << error;
  EXPECT_DOUBLE_EQ(ReadTimeOffsetState(path, &error)->offset_s, 0.004);
}

TEST(TimeOffsetState, TheFileSaysWhatItIsAndHowToForgetIt) {
  const std::string text = FormatTimeOffsetState(Example());
  EXPECT_THAT(text, HasSubstr("format: swlio-time-offset 1\n"));
  EXPECT_THAT(text, HasSubstr("offset_s: -0.0103412\n"));
  EXPECT_THAT(text, HasSubstr("Delete the file"));
}

TEST(TimeOffsetState, MalformedFilesAreRefusedWithTheirReason) {
  const std::string good = FormatTimeOffsetState(Example());
  EXPECT_THAT(ParseError(""), HasSubstr("not a map"));
  EXPECT_THAT(ParseError("just text"), HasSubstr("not a map"));
  EXPECT_THAT(ParseError("{unclosed"), HasSubstr("not YAML"));
  EXPECT_THAT(ParseError("\x01\xff\xfe garbage: [\n"), HasSubstr("not YAML"));
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    const size_t at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return t.replace(at, from.size(), to);
  };
  struct Edit {
    const char* from;
    const char* to;
    const char* reason;
  };
  const Edit edits[] = {
      {"swlio-time-offset 1", "swlio-time-offset 2", "format"},
      {"format: swlio-time-offset 1\n", "", "format"},
      {"offset_s: -0.0103412\n", "", "offset_s: missing"},
      {"-0.0103412", "-10 ms", "offset_s: '-10 ms' is not"},
      {"-0.0103412", "nan", "offset_s: must be finite"},
      {"-0.0103412", "0.5", "within ±0.2 s"},
      {"-0.0103412", "[1, 2]", "offset_s: missing"},
      {"8.62e-05", "0", "sigma_s: must be positive"},
      {"8.62e-05", "-1e-4", "sigma_s"},
      {"8.62e-05", "1e-12", "from 1 ns"},
      {"updates: 1843", "updates: 0", "updates: must be"},
      {"updates: 1843", "updates: -3", "updates: '-3'"},
      {"2026-12-06T07:12:30Z", "a\\\"b", "saved_utc"},
  };
  for (const Edit& e : edits) EXPECT_THAT(ParseError(with(e.from, e.to)), HasSubstr(e.reason));
  EXPECT_THAT(ParseError(good + "extra: 1\n"), HasSubstr("extra: unknown key"));
  // Cut anywhere before its last value, the file is refused, never read in part.
  const size_t last_value = good.find("updates:");
  for (size_t n = 0; n < last_value; n += 7) {
    std::string error;
    EXPECT_FALSE(ParseTimeOffsetState(good.substr(0, n), &error)) << n;
  }
}

TEST(TimeOffsetState, FilesThatCannotBeReadOrWrittenSaySo) {
  const auto dir = test::MakeTempDir("time_offset_state_io");
  std::string error;
  EXPECT_FALSE(ReadTimeOffsetState(dir / "absent.yaml", &error));
  EXPECT_THAT(error, HasSubstr("absent.yaml"));
  std::ofstream(dir / "large.yaml") << std::string(100'000, '#');
  EXPECT_FALSE(ReadTimeOffsetState(dir / "large.yaml", &error));
  EXPECT_THAT(error, HasSubstr("not a time offset file"));
  std::ofstream(dir / "bad.yaml") << "format: swlio-time-offset 1\n";
  EXPECT_FALSE(ReadTimeOffsetState(dir / "bad.yaml", &error));
  EXPECT_THAT(error, HasSubstr("bad.yaml: offset_s: missing"));
  EXPECT_FALSE(WriteTimeOffsetState(dir / "no" / "such" / "dir.yaml", Example(), &error));
  EXPECT_THAT(error, HasSubstr("dir.yaml.tmp"));
}

}  // namespace
}  // namespace swlio::daemon
