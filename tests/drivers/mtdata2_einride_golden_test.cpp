// All five einride MTi-G-710 captures decode to the values in output.golden (xsens-go's
// decoded text for the same bytes) and frame to the hex messages in messages.golden. The
// golden files are parsed here; every value they print is compared, with a tolerance of half
// a unit in the last printed digit.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus_messages.h"
#include "test_data.h"
#include "xsens_test_util.h"

namespace swlio::drivers::xsens {
namespace {

struct GoldenItem {
  std::string name;                                         ///< e.g. "Acceleration"
  std::string args;                                         ///< e.g. "EastNorthUp,Float32" or ""
  std::vector<std::pair<std::string, std::string>> values;  ///< key ("" for bare) → text
};
using GoldenMessage = std::vector<GoldenItem>;

std::vector<GoldenMessage> ParseGolden(const std::string& text) {
  std::vector<GoldenMessage> messages(1);
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) {
      if (!messages.back().empty()) messages.emplace_back();
      continue;
    }
    if (line.rfind("  ", 0) == 0) {
      if (messages.back().empty()) continue;
      GoldenItem& item = messages.back().back();
      const std::string body = line.substr(2);
      const size_t colon = body.find(':');
      if (item.name == "UTCTime" || colon == std::string::npos) {
        item.values.emplace_back("", body);
      } else {
        item.values.emplace_back(body.substr(0, colon), body.substr(colon + 1));
      }
      continue;
    }
    GoldenItem item;
    const size_t paren = line.find('(');
    item.name = line.substr(0, paren == std::string::npos ? line.size() - 1 : paren);
    if (paren != std::string::npos) item.args = line.substr(paren + 1, line.find(')') - paren - 1);
    messages.back().push_back(item);
  }
  if (messages.back().empty()) messages.pop_back();
  return messages;
}

/// Half a unit in the last printed digit of `text` (e.g. "3.34508175e+06" → 0.005).
double PrintedTolerance(const std::string& text) {
  const size_t e = text.find_first_of("eE");
  const std::string mantissa = text.substr(0, e);
  const int exponent = e == std::string::npos ? 0 : std::stoi(text.substr(e + 1));
  const size_t dot = mantissa.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  return 0.5 * std::pow(10.0, exponent - decimals);
}

void ExpectPrinted(double got, const std::string& text, const std::string& what) {
  const double want = std::stod(text);
  EXPECT_NEAR(got, want, PrintedTolerance(text) + 1e-15 * std::abs(want)) << what << " = " << text;
}

const std::map<std::string, std::optional<XsensReal> MtData2Sample::*>& RealFields() {
  static const std::map<std::string, std::optional<XsensReal> MtData2Sample::*> m = {
      {"Acceleration", &MtData2Sample::acc_mps2},
      {"DeltaV", &MtData2Sample::delta_v_mps},
      {"RateOfTurn", &MtData2Sample::rate_of_turn_radps},
      {"DeltaQ", &MtData2Sample::delta_q},
      {"EulerAngles", &MtData2Sample::euler_deg},
      {"LatLon", &MtData2Sample::lat_lon_deg},
      {"AltitudeEllipsoid", &MtData2Sample::altitude_ellipsoid_m},
      {"VelocityXYZ", &MtData2Sample::velocity_mps},
      {"FreeAcceleration", &MtData2Sample::free_acc_mps2},
      {"Quaternion", &MtData2Sample::quaternion},
      {"RotationMatrix", &MtData2Sample::rotation_matrix},
      {"Temperature", &MtData2Sample::temperature_degc},
      {"MagneticField", &MtData2Sample::mag_au},
      {"PositionECEF", &MtData2Sample::position_ecef_m},
  };
  return m;
}

std::string PrecisionName(XsensPrecision p) {
  switch (p) {
    case XsensPrecision::kFloat32:
      return "Float32";
    case XsensPrecision::kFp1220:
      return "FP1220";
    case XsensPrecision::kFp1632:
      return "FP1632";
    case XsensPrecision::kFloat64:
      return "Float64";
  }
  return "?";
}

std::string FrameName(XsensFrame f) {
  switch (f) {
    case XsensFrame::kEnu:
      return "EastNorthUp";
    case XsensFrame::kNed:
      return "NorthEastDown";
    case XsensFrame::kNwu:
      return "NorthWestUp";
  }
  return "?";
}

void CheckReal(const GoldenItem& g, const XsensReal& r) {
  const std::string expect_args =
      (g.args.find(',') != std::string::npos ? FrameName(r.frame) + "," : "") +
      PrecisionName(r.precision);
  EXPECT_EQ(g.args, expect_args) << g.name;
  ASSERT_EQ(g.values.size(), r.count) << g.name;
  for (size_t i = 0; i < r.count; ++i) ExpectPrinted(r.v[i], g.values[i].second, g.name);
}

void CheckUtc(const GoldenItem& g, const XsensUtcTime& t) {
  ASSERT_EQ(g.values.size(), 1u);
  const std::string& s = g.values[0].second;  // 2019-01-20T13:47:24.1219Z
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0;
  ASSERT_EQ(std::sscanf(s.c_str(), "%d-%d-%dT%d:%d:%d", &y, &mo, &d, &h, &mi, &sec), 6) << s;
  uint32_t ns = 0;
  const size_t dot = s.find('.');
  if (dot != std::string::npos) {
    std::string frac = s.substr(dot + 1, s.size() - dot - 2);
    frac.resize(9, '0');
    ns = static_cast<uint32_t>(std::stoul(frac));
  }
  EXPECT_EQ(t.year, y);
  EXPECT_EQ(t.month, mo);
  EXPECT_EQ(t.day, d);
  EXPECT_EQ(t.hour, h);
  EXPECT_EQ(t.minute, mi);
  EXPECT_EQ(t.second, sec);
  EXPECT_EQ(t.nanoseconds, ns) << s;
}

int64_t PvtField(const XsensGnssPvt& g, const std::string& key) {
  const std::map<std::string, int64_t> m = {{"ITOW", g.itow_ms},
                                            {"Year", g.year},
                                            {"Month", g.month},
                                            {"Day", g.day},
                                            {"Hour", g.hour},
                                            {"Min", g.min},
                                            {"Sec", g.sec},
                                            {"Valid", g.valid},
                                            {"TAcc", g.t_acc_ns},
                                            {"Nano", g.nano_ns},
                                            {"FixType", g.fix_type},
                                            {"Flags", g.flags},
                                            {"NumSV", g.num_sv},
                                            {"Reserved1", g.reserved1},
                                            {"Lon", g.lon_1e7deg},
                                            {"Lat", g.lat_1e7deg},
                                            {"Height", g.height_mm},
                                            {"HMSL", g.hmsl_mm},
                                            {"HAcc", g.h_acc_mm},
                                            {"VAcc", g.v_acc_mm},
                                            {"VelN", g.vel_n_mmps},
                                            {"VelE", g.vel_e_mmps},
                                            {"VelD", g.vel_d_mmps},
                                            {"GSpeed", g.g_speed_mmps},
                                            {"HeadMot", g.head_mot_1e5deg},
                                            {"SAcc", g.s_acc_mmps},
                                            {"HeadAcc", g.head_acc_1e5deg},
                                            {"HeadVeh", g.head_veh_1e5deg},
                                            {"GDOP", g.gdop},
                                            {"PDOP", g.pdop},
                                            {"TDOP", g.tdop},
                                            {"VDOP", g.vdop},
                                            {"HDOP", g.hdop},
                                            {"NDOP", g.ndop},
                                            {"EDOP", g.edop}};
  const auto it = m.find(key);
  return it == m.end() ? INT64_MIN : it->second;
}

uint16_t TypeByName(const std::string& name) {
  static const std::map<std::string, uint16_t> m = {{"PacketCounter", xdi::kPacketCounter},
                                                    {"SampleTimeFine", xdi::kSampleTimeFine},
                                                    {"SampleTimeCoarse", xdi::kSampleTimeCoarse},
                                                    {"UTCTime", xdi::kUtcTime},
                                                    {"StatusWord", xdi::kStatusWord},
                                                    {"StatusByte", xdi::kStatusByte},
                                                    {"Acceleration", xdi::kAcceleration},
                                                    {"DeltaV", xdi::kDeltaV},
                                                    {"RateOfTurn", xdi::kRateOfTurn},
                                                    {"DeltaQ", xdi::kDeltaQ},
                                                    {"EulerAngles", xdi::kEulerAngles},
                                                    {"LatLon", xdi::kLatLon},
                                                    {"AltitudeEllipsoid", xdi::kAltitudeEllipsoid},
                                                    {"VelocityXYZ", xdi::kVelocityXyz},
                                                    {"GNSSPVTData", xdi::kGnssPvtData},
                                                    {"GNSSSatInfo", xdi::kGnssSatInfo},
                                                    {"FreeAcceleration", xdi::kFreeAcceleration},
                                                    {"Quaternion", xdi::kQuaternion},
                                                    {"RotationMatrix", xdi::kRotationMatrix},
                                                    {"Temperature", xdi::kTemperature},
                                                    {"MagneticField", xdi::kMagneticField},
                                                    {"PositionECEF", xdi::kPositionEcef},
                                                    {"BaroPressure", xdi::kBaroPressure}};
  const auto it = m.find(name);
  return it == m.end() ? 0 : it->second;
}

/// Precision bits named in golden arguments ("EastNorthUp,FP1220" → 1); 0 when none.
uint16_t PrecisionBits(const std::string& args) {
  if (args.find("FP1220") != std::string::npos) return 1;
  if (args.find("FP1632") != std::string::npos) return 2;
  if (args.find("Float64") != std::string::npos) return 3;
  return 0;
}

uint64_t Binary(const std::string& bits) { return std::stoull(bits, nullptr, 2); }
int64_t Int(const GoldenItem& g) { return std::stoll(g.values.at(0).second); }

/// Compares one golden item; returns false when the item name is not known to the test.
bool CheckItem(const GoldenItem& g, const MtData2Sample& s) {
  const auto& reals = RealFields();
  if (const auto it = reals.find(g.name); it != reals.end()) {
    const auto& field = s.*(it->second);
    EXPECT_TRUE(field.has_value()) << g.name;
    if (field) CheckReal(g, *field);
  } else if (g.name == "PacketCounter") {
    EXPECT_EQ(s.packet_counter, Int(g));
  } else if (g.name == "SampleTimeFine") {
    EXPECT_EQ(s.sample_time_fine, Int(g));
  } else if (g.name == "SampleTimeCoarse") {
    EXPECT_EQ(s.sample_time_coarse, Int(g));
  } else if (g.name == "BaroPressure") {
    EXPECT_EQ(s.baro_pressure_pa, Int(g));
  } else if (g.name == "StatusWord") {
    EXPECT_EQ(g.values.at(0).second.size(), 32u);
    EXPECT_EQ(s.status_word, Binary(g.values.at(0).second));
  } else if (g.name == "StatusByte") {
    EXPECT_EQ(g.values.at(0).second.size(), 8u);
    EXPECT_EQ(s.status_byte, Binary(g.values.at(0).second));
  } else if (g.name == "UTCTime") {
    EXPECT_TRUE(s.utc_time.has_value());
    if (s.utc_time) CheckUtc(g, *s.utc_time);
  } else if (g.name == "GNSSPVTData") {
    EXPECT_TRUE(s.gnss_pvt.has_value());
    EXPECT_EQ(g.values.size(), 35u);
    for (const auto& [key, text] : g.values) {
      if (s.gnss_pvt) {
        EXPECT_EQ(PvtField(*s.gnss_pvt, key), std::stoll(text)) << key;
      }
    }
  } else if (g.name == "GNSSSatInfo") {
    EXPECT_TRUE(s.gnss_sat_info.has_value());
    if (!s.gnss_sat_info) return true;
    const XsensGnssSatInfo& si = *s.gnss_sat_info;
    const std::map<std::string, int64_t> m = {{"ITOW", si.itow_ms},
                                              {"NumSVS", si.num_svs},
                                              {"Res1", si.res1},
                                              {"Res2", si.res2},
                                              {"Res3", si.res3}};
    for (const auto& [key, text] : g.values) EXPECT_EQ(m.at(key), std::stoll(text)) << key;
    EXPECT_EQ(si.stored, si.num_svs);
  } else {
    return false;
  }
  return true;
}

class EinrideGolden : public ::testing::TestWithParam<int> {};

TEST_P(EinrideGolden, DecodesToEveryGoldenValue) {
  const std::string dir = "xsens_einride_mti-g-710/" + std::to_string(GetParam()) + "/";
  SWLIO_REQUIRE_DATA(bin, dir + "output.bin");
  SWLIO_REQUIRE_DATA(golden, dir + "output.golden");
  const auto bytes = test::ReadBytes(bin);
  XbusFramerStats stats;
  const auto frames = test::CollectFrames(bytes, 4096, &stats);
  const auto messages = ParseGolden(test::ReadText(golden));
  ASSERT_EQ(frames.size(), 100u);
  ASSERT_EQ(messages.size(), frames.size());
  EXPECT_EQ(stats.checksum_errors, 0u);
  EXPECT_EQ(stats.skipped_bytes, 0u);
  size_t values_compared = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("message " + std::to_string(i));
    ASSERT_EQ(frames[i].mid, 0x36);
    MtData2Sample s;
    ASSERT_EQ(DecodeMtData2(frames[i].payload, &s), MtData2Status::kOk);
    EXPECT_EQ(s.unknown_items, 0u);
    EXPECT_EQ(s.bad_size_items, 0u);
    ASSERT_EQ(s.item_count, messages[i].size()) << "items decoded vs golden";
    for (size_t k = 0; k < messages[i].size(); ++k) {
      const GoldenItem& g = messages[i][k];
      EXPECT_EQ(s.item_ids[k], TypeByName(g.name) | PrecisionBits(g.args)) << "order, " << g.name;
      EXPECT_TRUE(CheckItem(g, s)) << "golden item the test does not know: " << g.name;
      values_compared += g.values.size();
    }
  }
  EXPECT_GT(values_compared, 1000u);
}

TEST_P(EinrideGolden, FramesMatchMessagesGolden) {
  const std::string dir = "xsens_einride_mti-g-710/" + std::to_string(GetParam()) + "/";
  SWLIO_REQUIRE_DATA(bin, dir + "output.bin");
  SWLIO_REQUIRE_DATA(golden, dir + "messages.golden");
  const auto frames = test::CollectFrames(test::ReadBytes(bin), 1);
  std::istringstream in(test::ReadText(golden));
  std::string line;
  size_t i = 0;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    ASSERT_LT(i, frames.size());
    std::string hex;
    for (uint8_t b : frames[i].wire) {
      char buf[3];
      std::snprintf(buf, sizeof buf, "%02x", b);
      hex += buf;
    }
    EXPECT_EQ(hex, line) << "frame " << i;
    ++i;
  }
  EXPECT_EQ(i, frames.size());
}

TEST_P(EinrideGolden, OutputConfigurationMatchesGolden) {
  const std::string dir = "xsens_einride_mti-g-710/" + std::to_string(GetParam()) + "/";
  SWLIO_REQUIRE_DATA(bin, dir + "outputconfig.bin");
  SWLIO_REQUIRE_DATA(golden, dir + "outputconfig.golden");
  const auto bytes = test::ReadBytes(bin);
  const auto entries = ParseGolden(test::ReadText(golden));
  ASSERT_EQ(entries.size(), 1u);
  std::array<XsensOutputItem, 32> items;
  const std::optional<size_t> n = ParseOutputConfiguration(bytes, items);
  ASSERT_TRUE(n.has_value());
  ASSERT_EQ(*n, entries[0].size());
  for (size_t i = 0; i < *n; ++i) {
    const GoldenItem& g = entries[0][i];
    EXPECT_EQ(items[i].xdi, TypeByName(g.name) | PrecisionBits(g.args)) << g.name;
    const uint16_t rate = items[i].rate_hz;
    const std::string& text = g.values.at(0).second;
    if (text == "Max") {
      EXPECT_EQ(rate, 0xFFFF);
    } else {
      EXPECT_EQ(std::to_string(rate) + " Hz", text);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Sets, EinrideGolden, ::testing::Values(1, 2, 3, 4, 5));

}  // namespace
}  // namespace swlio::drivers::xsens
