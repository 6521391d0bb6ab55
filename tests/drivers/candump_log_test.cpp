#include "swlio/drivers/candump_log.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>

namespace swlio::drivers {
namespace {

TEST(CandumpLine, ParsesStandardExtendedRemoteAndErrorFrames) {
  CandumpRecord r;
  ASSERT_EQ(ParseCandumpLine("(1700000000.123456) can0 123#DEADBEEF\n", &r),
            CandumpLineStatus::kFrame);
  EXPECT_EQ(r.t_ns, 1'700'000'000'123'456'000);
  EXPECT_EQ(r.interface_name(), "can0");
  EXPECT_EQ(r.frame.id, 0x123u);
  EXPECT_FALSE(r.frame.extended);
  EXPECT_EQ(r.frame.dlc, 4);
  EXPECT_EQ(r.frame.data[0], 0xDE);
  EXPECT_EQ(r.frame.data[3], 0xEF);

  ASSERT_EQ(ParseCandumpLine("(0000000001.5) vcan10 1ABCDEF0#01.02.03", &r),
            CandumpLineStatus::kFrame);
  EXPECT_EQ(r.t_ns, 1'500'000'000);
  EXPECT_TRUE(r.frame.extended);
  EXPECT_EQ(r.frame.id, 0x1ABCDEF0u);
  EXPECT_EQ(r.frame.dlc, 3);
  EXPECT_EQ(r.frame.data[2], 3);

  ASSERT_EQ(ParseCandumpLine("(1.000000) can0 7FF#R", &r), CandumpLineStatus::kFrame);
  EXPECT_TRUE(r.frame.remote);
  EXPECT_EQ(r.frame.dlc, 0);
  ASSERT_EQ(ParseCandumpLine("(1.000000) can0 00000123#R6", &r), CandumpLineStatus::kFrame);
  EXPECT_TRUE(r.frame.remote);
  EXPECT_TRUE(r.frame.extended);
  EXPECT_EQ(r.frame.dlc, 6);

  ASSERT_EQ(ParseCandumpLine("(1.000000) can0 20000004#0004000000000000", &r),
            CandumpLineStatus::kFrame);
  EXPECT_TRUE(r.frame.error);
  EXPECT_FALSE(r.frame.extended);
  EXPECT_EQ(r.frame.id, 0x4u);
  EXPECT_EQ(r.frame.dlc, 8);

  // A trailing direction flag (" R" received / " T" transmitted) is not a remote frame.
  ASSERT_EQ(ParseCandumpLine("(1.000000) can0 100# R", &r), CandumpLineStatus::kFrame);
  EXPECT_FALSE(r.frame.remote);
  ASSERT_EQ(ParseCandumpLine("(1.000000) can0 100#0102 T", &r), CandumpLineStatus::kFrame);
  EXPECT_EQ(r.frame.dlc, 2);
  ASSERT_EQ(ParseCandumpLine("(1.000000) can0 100#", &r), CandumpLineStatus::kFrame);
  EXPECT_EQ(r.frame.dlc, 0);
}

TEST(CandumpLine, ClassifiesEverythingElse) {
  CandumpRecord r;
  r.t_ns = 42;
  EXPECT_EQ(ParseCandumpLine("", &r), CandumpLineStatus::kBlank);
  EXPECT_EQ(ParseCandumpLine("   \r\n", &r), CandumpLineStatus::kBlank);
  EXPECT_EQ(ParseCandumpLine("# recorded on the chassis", &r), CandumpLineStatus::kBlank);
  EXPECT_EQ(ParseCandumpLine("(1.0) can0 123##1DEADBEEF", &r), CandumpLineStatus::kCanFd);
  for (std::string_view bad : std::initializer_list<std::string_view>{
           "(1.0) can0 800#00",                            // standard id > 0x7FF
           "(1.0) can0 12#00",                             // 2-digit id
           "(1.0) can0 1234#00",                           // 4-digit id
           "(1.0) can0 40000000#00",                       // RTR flag bit in an 8-digit id
           "(1.0) can0 123#0",                             // half a byte
           "(1.0) can0 123#001122334455667788",            // 9 bytes
           "(1.0) can0 123#GG",                            // not hex
           "(1.0) can0 123#R9",                            // remote DLC > 8
           "(1.0) can0 123",                               // no '#'
           "(1.0) can0",                                   // no frame
           "1.0 can0 123#00",                              // no parentheses
           "(1.) can0 123#00",                             // no fraction
           "(.5) can0 123#00",                             // no seconds
           "(1.0000000001) can0 123#00",                   // 10 fraction digits
           "(99999999999999.0) can0 123#00",               // seconds would overflow
           "(9999999999.0) can0 123#00",                   // 10 digits, still past int64 ns
           "(1.0 can0 123#00",                             // unclosed
           std::string_view("(1.0) \0\ncan0 123#00", 20),  // control characters in the name
           "(1.0) averyveryverylongifname 123#00",
           "(1.0) can0 123#00 X",  // unknown trailing flag
           "(1.0) can0 123#00 T extra",
           "(-1.0) can0 123#00",
       }) {
    EXPECT_EQ(ParseCandumpLine(bad, &r), CandumpLineStatus::kMalformed) << bad;
  }
  EXPECT_EQ(r.t_ns, 42);  // untouched by failures
}

TEST(CandumpLine, FormatsLikeCandump) {
  CanFrame f;
  f.id = 0x123;
  f.dlc = 4;
  f.data = {0xDE, 0xAD, 0xBE, 0xEF};
  std::array<char, kCandumpMaxLineBytes> buf{};
  size_t n = FormatCandumpLine(MakeCandumpRecord(1'700'000'000'123'456'789, "can0", f), buf);
  EXPECT_EQ(std::string(buf.data(), n), "(1700000000.123456) can0 123#DEADBEEF\n");
  f.id = 0xAB;
  f.extended = true;
  f.remote = true;
  f.dlc = 3;
  n = FormatCandumpLine(MakeCandumpRecord(5, "vcan0", f), buf);
  EXPECT_EQ(std::string(buf.data(), n), "(0000000000.000000) vcan0 000000AB#R3\n");
  f.extended = false;
  f.remote = false;
  f.id = 0x800;  // not a standard id
  EXPECT_EQ(FormatCandumpLine(MakeCandumpRecord(5, "can0", f), buf), 0u);
  f.id = 1;
  EXPECT_EQ(FormatCandumpLine(MakeCandumpRecord(-5, "can0", f), buf), 0u);
  EXPECT_EQ(FormatCandumpLine(MakeCandumpRecord(5, "", f), buf), 0u);
}

TEST(CandumpLog, RandomFramesRoundTripThroughAStream) {
  std::mt19937 rng(7);
  std::vector<CandumpRecord> written;
  std::stringstream log;
  for (int i = 0; i < 2000; ++i) {
    CanFrame f;
    f.extended = rng() % 2 == 0;
    f.error = !f.extended && rng() % 50 == 0;
    f.remote = !f.error && rng() % 10 == 0;
    f.id = static_cast<uint32_t>(rng()) & (f.extended || f.error ? kCanMaxExtendedId : 0x7FFu);
    f.dlc = static_cast<uint8_t>(rng() % 9);
    if (!f.remote) {
      for (size_t k = 0; k < f.dlc; ++k) f.data[k] = static_cast<uint8_t>(rng());
    }
    const int64_t t_ns = static_cast<int64_t>(rng()) * 1000 + 1'600'000'000'000'000'000;
    written.push_back(MakeCandumpRecord(t_ns, i % 2 ? "can0" : "can1", f));
    ASSERT_TRUE(WriteCandumpLine(log, written.back()));
    if (i % 100 == 0) log << "garbage line " << i << "\n\n";
  }
  CandumpReader reader(log);
  CandumpRecord r;
  size_t i = 0;
  while (reader.Next(&r)) {
    ASSERT_LT(i, written.size());
    const CandumpRecord& w = written[i++];
    EXPECT_EQ(r.t_ns, w.t_ns);
    EXPECT_EQ(r.interface_name(), w.interface_name());
    EXPECT_EQ(r.frame.id, w.frame.id);
    EXPECT_EQ(r.frame.extended, w.frame.extended);
    EXPECT_EQ(r.frame.error, w.frame.error);
    EXPECT_EQ(r.frame.remote, w.frame.remote);
    EXPECT_EQ(r.frame.dlc, w.frame.dlc);
    EXPECT_EQ(r.frame.data, w.frame.data);
  }
  EXPECT_EQ(i, written.size());
  EXPECT_EQ(reader.counters().frames, 2000u);
  EXPECT_EQ(reader.counters().malformed_lines, 20u);
  EXPECT_EQ(reader.counters().blank_lines, 20u);
}

}  // namespace
}  // namespace swlio::drivers
