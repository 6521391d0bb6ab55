#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "swlio/daemon/config/config_loader.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

constexpr const char* kCanLayout = R"(config_version: 1
can:
  enabled: true
  interface: can1
  mode: wheel_speeds
  wheel_speed_unit: radps
  wheel_radius_m: 0.15
  track_width_m: 0.62
  max_pair_skew_s: 0.02
  signals:
    - role: left_wheel_speed
      can_id: 0x18FF0101
      extended: true
      byte_offset: 0
      length_bits: 16
      byte_order: motorola
      signed: true
      scale: 0.01
      offset: 0.5
      dlc: 8
    - role: right_wheel_speed
      can_id: 513
      start_bit: 16
      length_bits: 12
      byte_order: intel
      signed: false
      scale: -0.01
)";

TEST(CanConfigLoader, LoadsTheSignalList) {
  const LoadedConfig loaded = LoadConfigText(kCanLayout, "can.yaml", "/tmp");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  const drivers::CanConfig& c = loaded.config.can;
  EXPECT_TRUE(c.enabled);
  EXPECT_EQ(c.interface, "can1");
  EXPECT_EQ(c.wheel_speed_unit, "radps");
  EXPECT_DOUBLE_EQ(c.wheel_radius_m, 0.15);
  EXPECT_DOUBLE_EQ(c.track_width_m, 0.62);
  EXPECT_DOUBLE_EQ(c.max_pair_skew_s, 0.02);
  ASSERT_EQ(c.signals.size(), 2u);
  EXPECT_EQ(c.signals[0].role, "left_wheel_speed");
  EXPECT_EQ(c.signals[0].can_id, 0x18FF0101);
  EXPECT_TRUE(c.signals[0].extended);
  EXPECT_EQ(c.signals[0].byte_offset, 0);
  EXPECT_EQ(c.signals[0].start_bit, -1);
  EXPECT_EQ(c.signals[0].byte_order, "motorola");
  EXPECT_DOUBLE_EQ(c.signals[0].offset, 0.5);
  EXPECT_EQ(c.signals[0].dlc, 8);
  EXPECT_EQ(c.signals[1].can_id, 513);
  EXPECT_EQ(c.signals[1].start_bit, 16);
  EXPECT_EQ(c.signals[1].length_bits, 12);
  EXPECT_FALSE(c.signals[1].is_signed);
  EXPECT_DOUBLE_EQ(c.signals[1].scale, -0.01);
}

TEST(CanConfigLoader, ReportsSignalProblemsWithTheirPlace) {
  std::string text = kCanLayout;
  text.replace(text.find("can_id: 513"), 11, "can_id: 0x800");  // > 11 bits
  text.replace(text.find("length_bits: 12"), 15, "lenght_bits: 12");
  text += "    - 42\n";
  const LoadedConfig loaded = LoadConfigText(text, "can.yaml", "/tmp");
  ASSERT_FALSE(loaded.ok());
  const std::string report = loaded.ErrorReport();
  EXPECT_NE(report.find("can.yaml:22:7: can.signals[1].can_id: must be in [0, 2047]"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("can.signals[1].lenght_bits: unknown key (did you mean 'length_bits'?)"),
            std::string::npos)
      << report;
  EXPECT_NE(report.find("can.signals[2]: expected a mapping"), std::string::npos) << report;
  EXPECT_EQ(loaded.errors.size(), 3u) << report;
}

TEST(CanConfigLoader, AnEnabledInputNeedsBothSignals) {
  std::string text = kCanLayout;
  text.erase(text.find("    - role: right_wheel_speed"));
  const LoadedConfig loaded = LoadConfigText(text, "can.yaml", "/tmp");
  EXPECT_NE(loaded.ErrorReport().find("can.yaml:10:3: can.signals: mode wheel_speeds needs "
                                      "exactly one left_wheel_speed and one right_wheel_speed"),
            std::string::npos)
      << loaded.ErrorReport();
}

TEST(CanConfigLoader, RejectsAListThatIsNotAList) {
  const LoadedConfig loaded =
      LoadConfigText("config_version: 1\ncan:\n  signals: {role: x}\n", "c.yaml", "/tmp");
  ASSERT_FALSE(loaded.ok());
  EXPECT_NE(loaded.ErrorReport().find("c.yaml:3:12: can.signals: expected a list of mappings"),
            std::string::npos)
      << loaded.ErrorReport();
}

TEST(CanConfigLoader, ShippedExampleLayoutIsValidWhenUncommented) {
  // config/swlio.yaml documents the layout in comments; uncommenting it must give a valid file.
  std::ifstream in(test::SourceDir() / "config" / "swlio.yaml");
  ASSERT_TRUE(in) << "config/swlio.yaml not found under " << test::SourceDir();
  std::stringstream out;
  std::string line;
  bool in_can = false;
  int uncommented = 0;
  const std::regex setting(R"(^  # ((  )*(- )?[a-z_]+:.*)$)");  // "  # key: …", "  #   - key: …"
  std::smatch m;
  while (std::getline(in, line)) {
    if (line.rfind("can:", 0) == 0) in_can = true;
    if (in_can && line.rfind("estimator:", 0) == 0) in_can = false;
    if (in_can && std::regex_match(line, m, setting)) {
      line = "  " + m[1].str();
      ++uncommented;
    }
    out << line << '\n';
  }
  EXPECT_GT(uncommented, 15);
  const std::string text = out.str();
  const LoadedConfig loaded = LoadConfigText(text, "swlio.yaml", test::SourceDir() / "config");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport() << "\n" << text;
  EXPECT_EQ(loaded.config.can.signals.size(), 2u);
}

}  // namespace
}  // namespace swlio::daemon
