// MTi-300 data (Scottapotamas/xsens-mti): the raw MTData2 payloads in mtmanager_packets.md
// decode to the values of Xsens MT Manager's "Decoded Info" line printed beside them (the raw
// bytes are authoritative; the document's per-item hand breakdown is not used), and the 16
// frames of test_frames_mti-300.bin frame and decode consistently in all four precisions.

#include <gtest/gtest.h>

#include <regex>
#include <sstream>

#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus_messages.h"
#include "test_data.h"
#include "xsens_test_util.h"

namespace swlio::drivers::xsens {
namespace {

struct MdPacket {
  std::vector<uint8_t> payload;
  std::string decoded;  ///< MT Manager line, empty when the document gives none
};

std::vector<MdPacket> ParseMarkdown(const std::string& text) {
  std::vector<MdPacket> packets;
  std::istringstream in(text);
  std::string line;
  enum { kNone, kRawHeader, kRaw, kDecodedHeader, kDecoded } state = kNone;
  while (std::getline(in, line)) {
    if (line.rfind("## Raw Data", 0) == 0) {
      packets.emplace_back();
      state = kRawHeader;
    } else if (line.rfind("## Decoded Info", 0) == 0 && !packets.empty()) {
      state = kDecodedHeader;
    } else if (line.rfind("```", 0) == 0) {
      state = state == kRawHeader ? kRaw : state == kDecodedHeader ? kDecoded : kNone;
    } else if (state == kRaw) {
      std::istringstream hex(line);
      std::string byte;
      while (hex >> byte)
        packets.back().payload.push_back(static_cast<uint8_t>(std::stoul(byte, nullptr, 16)));
    } else if (state == kDecoded) {
      packets.back().decoded += line;
    }
  }
  return packets;
}

/// "(Name|Float|ENU, 16 bytes, (k: v, …))" → name, size and the numbers after it.
struct MdItem {
  std::string name;
  size_t bytes = 0;
  std::vector<std::pair<std::string, std::string>> values;  ///< key ("" for bare) → text
};

std::vector<MdItem> SplitItems(const std::string& decoded) {
  std::vector<MdItem> items;
  const std::regex item_re(R"(\((\w+)[^,]*, (\d+) bytes, ([^()]*|\([^()]*\))\))");
  const std::regex value_re(R"((\w+):\s*(-?[0-9.]+))");
  for (std::sregex_iterator it(decoded.begin(), decoded.end(), item_re), end; it != end; ++it) {
    MdItem item{(*it)[1], std::stoul((*it)[2]), {}};
    const std::string body = (*it)[3];
    for (std::sregex_iterator v(body.begin(), body.end(), value_re); v != end; ++v) {
      item.values.emplace_back((*v)[1], (*v)[2]);
    }
    if (item.values.empty()) item.values.emplace_back("", body);
    items.push_back(item);
  }
  return items;
}

const std::optional<XsensReal>* RealFor(const MtData2Sample& s, const std::string& name) {
  if (name == "Quaternion") return &s.quaternion;
  if (name == "Acceleration") return &s.acc_mps2;
  if (name == "DeltaV") return &s.delta_v_mps;
  if (name == "FreeAcceleration") return &s.free_acc_mps2;
  if (name == "RateOfTurn") return &s.rate_of_turn_radps;
  if (name == "DeltaQ") return &s.delta_q;
  if (name == "MagneticField") return &s.mag_au;
  if (name == "Temperature") return &s.temperature_degc;
  return nullptr;
}

void CheckMdItem(const MdItem& item, const MtData2Sample& s) {
  SCOPED_TRACE(item.name);
  const std::string& first = item.values.at(0).second;
  if (item.name == "PacketCounter") {
    EXPECT_EQ(s.packet_counter, std::stoul(first));
  } else if (item.name == "SampleTimeFine") {
    EXPECT_EQ(s.sample_time_fine, std::stoul(first));
  } else if (item.name == "BaroPressure") {
    EXPECT_EQ(s.baro_pressure_pa, std::stoul(first));
  } else if (item.name == "StatusWord") {
    EXPECT_EQ(s.status_word, std::stoul(first, nullptr, 2));
  } else if (const auto* field = RealFor(s, item.name); field != nullptr) {
    ASSERT_TRUE(field->has_value());
    const XsensReal& r = **field;
    EXPECT_EQ(XsensValueSize(r.precision) * r.count, item.bytes);
    ASSERT_EQ(item.values.size(), r.count);
    for (size_t i = 0; i < r.count; ++i) {
      // MT Manager prints 8 decimals: half a unit in the last place.
      EXPECT_NEAR(r.v[i], std::stod(item.values[i].second), 0.5e-8 + 1e-12) << item.values[i].first;
    }
  } else {
    ADD_FAILURE() << "item not known to the test: " << item.name;
  }
}

TEST(MtData2Mti300, MarkdownPayloadsMatchMtManager) {
  SWLIO_REQUIRE_DATA(md, "xsens_scottapotamas_mti-300/mtmanager_packets.md");
  const auto packets = ParseMarkdown(test::ReadText(md));
  ASSERT_EQ(packets.size(), 6u);
  size_t compared = 0;
  for (size_t p = 0; p < packets.size(); ++p) {
    SCOPED_TRACE("packet " + std::to_string(p + 1));
    MtData2Sample s;
    ASSERT_EQ(DecodeMtData2(packets[p].payload, &s), MtData2Status::kOk);
    EXPECT_EQ(s.unknown_items, 0u);
    EXPECT_EQ(s.bad_size_items, 0u);
    const auto items = SplitItems(packets[p].decoded);
    ASSERT_FALSE(items.empty());
    ASSERT_EQ(items.size(), s.item_count);
    for (const MdItem& item : items) {
      CheckMdItem(item, s);
      compared += item.values.size();
    }
  }
  EXPECT_EQ(compared, 138u);  // every number on the six MT Manager lines
}

TEST(MtData2Mti300, CapturedFramesCarryTheDocumentedPayloads) {
  // Three of the captured Xbus frames hold exactly the payloads MT Manager decoded (examples
  // 4, 5 and 6), so the checked values above are also those of the framed captures.
  SWLIO_REQUIRE_DATA(md, "xsens_scottapotamas_mti-300/mtmanager_packets.md");
  SWLIO_REQUIRE_DATA(bin, "xsens_scottapotamas_mti-300/test_frames_mti-300.bin");
  const auto packets = ParseMarkdown(test::ReadText(md));
  const auto frames = test::CollectFrames(test::ReadBytes(bin), 16);
  std::vector<size_t> matched;
  for (size_t p = 0; p < packets.size(); ++p) {
    for (const auto& f : frames) {
      if (f.mid == 0x36 && f.payload == packets[p].payload) matched.push_back(p + 1);
    }
  }
  EXPECT_EQ(matched, (std::vector<size_t>{4, 5, 6}));
}

TEST(MtData2Mti300, CaptureFramesMatchTheirIndex) {
  SWLIO_REQUIRE_DATA(bin, "xsens_scottapotamas_mti-300/test_frames_mti-300.bin");
  SWLIO_REQUIRE_DATA(tsv, "xsens_scottapotamas_mti-300/test_frames_mti-300.index.tsv");
  XbusFramerStats stats;
  const auto frames = test::CollectFrames(test::ReadBytes(bin), 5, &stats);
  std::istringstream in(test::ReadText(tsv));
  std::string line;
  std::getline(in, line);  // header
  size_t i = 0;
  while (std::getline(in, line)) {
    size_t offset = 0, length = 0;
    char mid_text[8] = {};
    ASSERT_EQ(std::sscanf(line.c_str(), "%zu\t%zu\t%7s", &offset, &length, mid_text), 3);
    ASSERT_LT(i, frames.size());
    EXPECT_EQ(frames[i].wire.size(), length);
    EXPECT_EQ(frames[i].mid, std::stoul(mid_text, nullptr, 16));
    ++i;
  }
  EXPECT_EQ(i, 16u);
  EXPECT_EQ(frames.size(), 16u);
  EXPECT_EQ(stats.checksum_errors, 0u);
  EXPECT_EQ(stats.skipped_bytes, 0u);
  // OutputConfiguration ack echoes PacketCounter and SampleTimeFine at "every sample".
  std::array<XsensOutputItem, 8> items;
  ASSERT_EQ(ParseOutputConfiguration(frames[2].payload, items), 2u);
  EXPECT_EQ(items[0], (XsensOutputItem{0x1020, 0xFFFF}));
  EXPECT_EQ(items[1], (XsensOutputItem{0x1060, 0xFFFF}));
  EXPECT_EQ(ParseDeviceId(frames[3].payload), 0x037003F8u);  // InitMTResults carries the id
}

TEST(MtData2Mti300, RotationMatricesAreOrthonormalInEveryPrecision) {
  SWLIO_REQUIRE_DATA(bin, "xsens_scottapotamas_mti-300/test_frames_mti-300.bin");
  const auto frames = test::CollectFrames(test::ReadBytes(bin), 64);
  int seen_precisions = 0;
  for (const auto& f : frames) {
    if (f.mid != 0x36) continue;
    MtData2Sample s;
    ASSERT_EQ(DecodeMtData2(f.payload, &s), MtData2Status::kOk);
    EXPECT_EQ(s.unknown_items + s.bad_size_items, 0);
    if (s.quaternion) {
      const auto& q = s.quaternion->v;
      EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-5);
    }
    if (!s.rotation_matrix) continue;
    seen_precisions |= 1 << static_cast<int>(s.rotation_matrix->precision);
    Eigen::Matrix3d r;
    for (int k = 0; k < 9; ++k) r(k % 3, k / 3) = s.rotation_matrix->v[static_cast<size_t>(k)];
    EXPECT_TRUE((r * r.transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-5)) << r;
    EXPECT_NEAR(r.determinant(), 1.0, 1e-5);
  }
  EXPECT_EQ(seen_precisions, 0xF);  // Float32, FP12.20, FP16.32 and Float64 all seen
}

TEST(MtData2Mti300, MixedPrecisionFrameDecodes) {
  SWLIO_REQUIRE_DATA(bin, "xsens_scottapotamas_mti-300/test_frames_mti-300.bin");
  const auto frames = test::CollectFrames(test::ReadBytes(bin), 64);
  ASSERT_EQ(frames.size(), 16u);
  MtData2Sample s;  // test_parse_mdata2_number_formats: Euler FP12.20, ΔQ FP16.32, mag Float64
  ASSERT_EQ(DecodeMtData2(frames[10].payload, &s), MtData2Status::kOk);
  ASSERT_TRUE(s.euler_deg && s.delta_q && s.mag_au && s.temperature_degc);
  EXPECT_EQ(s.euler_deg->precision, XsensPrecision::kFp1220);
  EXPECT_EQ(s.delta_q->precision, XsensPrecision::kFp1632);
  EXPECT_EQ(s.mag_au->precision, XsensPrecision::kFloat64);
  const auto& dq = s.delta_q->v;
  EXPECT_NEAR(dq[0] * dq[0] + dq[1] * dq[1] + dq[2] * dq[2] + dq[3] * dq[3], 1.0, 1e-6);
  EXPECT_NEAR(s.temperature_degc->v[0], 27.4375, 1e-9);  // 0x41DB8000 as Float32
}

}  // namespace
}  // namespace swlio::drivers::xsens
