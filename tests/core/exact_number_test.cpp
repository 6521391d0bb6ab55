#include "swlio/core/exact_number.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <limits>
#include <random>

namespace swlio {
namespace {

TEST(ExactNumber, ReadsBackAsTheSameDouble) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> offset_s(1.7e9, 1.7e9 + 86400.0);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 10000; ++i) {
    for (const double v : {offset_s(rng), unit(rng), unit(rng) * 1e-7, unit(rng) * 1e25}) {
      const std::string text = ExactNumber(v);
      EXPECT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
      EXPECT_NE(text.find('.'), std::string::npos) << text;
    }
  }
}

// The case of issue 32: "%.10g" wrote a LiDAR clock offset of 1700081385.407 s as 1700081385.
TEST(ExactNumber, KeepsEveryDigitOfAClockOffset) {
  EXPECT_EQ(ExactNumber(1700081385.407), "1700081385.407");
  EXPECT_EQ(ExactNumber(600.0), "600.0");
  EXPECT_EQ(ExactNumber(1e-5), "1.0e-05");
  EXPECT_EQ(ExactNumber(-2.5e20), "-2.5e+20");
  EXPECT_EQ(ExactNumber(0.1), "0.1");
  EXPECT_EQ(ExactNumber(std::numeric_limits<double>::infinity()), "inf");
}

}  // namespace
}  // namespace swlio
