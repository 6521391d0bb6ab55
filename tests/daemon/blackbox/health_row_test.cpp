// health.csv rows (health_row.h): one field per header column, the time-offset, moving-point and
// operator-reset columns at the end.

#include "swlio/daemon/blackbox/health_row.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace swlio::daemon {
namespace {

std::vector<std::string> Fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

std::string Field(const std::string& row, const std::string& column) {
  const std::vector<std::string> names = Fields(kHealthCsvHeader);
  const std::vector<std::string> values = Fields(row);
  for (size_t i = 0; i < names.size() && i < values.size(); ++i) {
    if (names[i] == column) return values[i];
  }
  return "<missing>";
}

TEST(HealthCsvRow, OneFieldPerColumn) {
  HealthSnapshot s;
  const std::string row = HealthCsvRow(s, 5'000'000'000, 1'796'000'000'000'000'000, {});
  EXPECT_EQ(Fields(row).size(), Fields(kHealthCsvHeader).size());
  EXPECT_EQ(Field(row, "t_ns"), "5000000000");
}

TEST(HealthCsvRow, TimeOffsetMovingPointsAndOperatorResets) {
  HealthSnapshot s;
  EXPECT_EQ(Field(HealthCsvRow(s, 0, 0, {}), "imu_time_offset_sigma_ms"), "")
      << "no sigma before the estimator has rows";
  s.optimizer.time_offset.offset_s = -0.00125;
  s.optimizer.time_offset.sigma_s = 0.0004;
  s.optimizer.dynamic_removed = 1234;
  s.optimizer.reinitializations = 3;
  s.optimizer.operator_resets = 2;
  const std::string row = HealthCsvRow(s, 0, 0, {});
  EXPECT_EQ(Field(row, "imu_time_offset_ms"), "-1.25");
  EXPECT_EQ(Field(row, "imu_time_offset_sigma_ms"), "0.4");
  EXPECT_EQ(Field(row, "moving_points_removed"), "1234");
  EXPECT_EQ(Field(row, "estimator_reinitializations"), "3");
  EXPECT_EQ(Field(row, "estimator_operator_resets"), "2") << "of the 3, asked for by swlioctl";
  EXPECT_EQ(Fields(row).size(), Fields(kHealthCsvHeader).size());
}

}  // namespace
}  // namespace swlio::daemon
