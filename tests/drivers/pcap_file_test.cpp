#include "swlio/drivers/pcap_file.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <vector>

#include "swlio/drivers/bytes.h"
#include "test_data.h"

namespace swlio::drivers {
namespace {

using Bytes = std::vector<uint8_t>;

void WriteFile(const std::filesystem::path& path, const Bytes& data) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
}

Bytes ReadFile(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(f), {});
}

// IPv4 + UDP carrying `payload` (checksums zero; the reader does not verify them).
Bytes Ipv4Udp(uint16_t src_port, uint16_t dst_port, const Bytes& payload, uint8_t proto = 17) {
  Bytes ip(28 + payload.size(), 0);
  ip[0] = 0x45;
  bytes::WriteU16Be(&ip[2], static_cast<uint16_t>(ip.size()));
  ip[8] = 64;
  ip[9] = proto;
  ip[12] = 10, ip[15] = 1, ip[16] = 10, ip[19] = 2;
  bytes::WriteU16Be(&ip[20], src_port);
  bytes::WriteU16Be(&ip[22], dst_port);
  bytes::WriteU16Be(&ip[24], static_cast<uint16_t>(8 + payload.size()));
  std::copy(payload.begin(), payload.end(), ip.begin() + 28);
  return ip;
}

Bytes Ethernet(const Bytes& ip, uint16_t ether_type = 0x0800) {
  Bytes f(14 + ip.size(), 0);
  bytes::WriteU16Be(&f[12], ether_type);
  std::copy(ip.begin(), ip.end(), f.begin() + 14);
  return f;
}

// Classic little-endian µs pcap with the given link type and records.
Bytes ClassicPcap(uint32_t linktype, const std::vector<Bytes>& records) {
  Bytes out(24, 0);
  bytes::WriteU32Le(&out[0], 0xA1B2C3D4);
  out[4] = 2, out[6] = 4;
  bytes::WriteU32Le(&out[16], 65535);
  bytes::WriteU32Le(&out[20], linktype);
  uint32_t sec = 100;
  for (const Bytes& r : records) {
    Bytes h(16, 0);
    bytes::WriteU32Le(&h[0], sec++);
    bytes::WriteU32Le(&h[4], 250);
    bytes::WriteU32Le(&h[8], static_cast<uint32_t>(r.size()));
    bytes::WriteU32Le(&h[12], static_cast<uint32_t>(r.size()));
    out.insert(out.end(), h.begin(), h.end());
    out.insert(out.end(), r.begin(), r.end());
  }
  return out;
}

std::vector<UdpDatagram> ReadAll(const std::filesystem::path& path,
                                 PcapUdpFilter filter,
                                 std::vector<Bytes>* payloads,
                                 PcapReadStats* stats = nullptr,
                                 std::string* read_error = nullptr) {
  std::string error;
  auto reader = PcapReader::Open(path.string(), std::move(filter), &error);
  EXPECT_NE(reader, nullptr) << error;
  std::vector<UdpDatagram> out;
  if (!reader) return out;
  UdpDatagram d;
  while (reader->Next(&d)) {
    out.push_back(d);
    payloads->emplace_back(d.payload.begin(), d.payload.end());
  }
  if (stats != nullptr) *stats = reader->stats();
  if (read_error != nullptr) *read_error = reader->error();
  return out;
}

TEST(PcapFile, WriterReaderRoundTripWithPortFilter) {
  const auto dir = test::MakeTempDir("pcap_rt");
  const auto path = dir / "rt.pcap";
  std::vector<Bytes> sent;
  {
    std::string error;
    auto writer = PcapWriter::Create(path.string(), {}, &error);
    ASSERT_NE(writer, nullptr) << error;
    for (int i = 0; i < 10; ++i) {
      Bytes payload(static_cast<size_t>(1 + i * 137), static_cast<uint8_t>(i));
      sent.push_back(payload);
      const uint16_t port = i % 3 == 0 ? 7788 : 6699;
      ASSERT_TRUE(
          writer->Write(1'600'000'000'123'456'789 + int64_t{i} * 1'000'001, 1000, port, payload));
    }
    ASSERT_TRUE(writer->Flush());
  }
  std::vector<Bytes> got;
  PcapReadStats stats;
  const auto all = ReadAll(path, {}, &got, &stats);
  ASSERT_EQ(all.size(), sent.size());
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(got[i], sent[i]);
    EXPECT_EQ(all[i].t_ns, 1'600'000'000'123'456'789 + static_cast<int64_t>(i) * 1'000'001);
    EXPECT_EQ(all[i].src_port, 1000);
    EXPECT_EQ(all[i].dst_ip, (std::array<uint8_t, 4>{127, 0, 0, 1}));
  }
  EXPECT_EQ(stats.records, 10u);
  EXPECT_EQ(stats.malformed, 0u);

  std::vector<Bytes> difop;
  PcapUdpFilter only_difop;
  only_difop.dst_ports = {7788};
  const auto filtered = ReadAll(path, only_difop, &difop, &stats);
  ASSERT_EQ(filtered.size(), 4u);  // i = 0, 3, 6, 9
  EXPECT_EQ(difop[1], sent[3]);
  EXPECT_EQ(stats.filtered_out, 6u);
  PcapUdpFilter wrong_src;
  wrong_src.src_ports = {1};
  EXPECT_TRUE(ReadAll(path, wrong_src, &difop).empty());
}

TEST(PcapFile, MicrosecondWriterTruncatesTime) {
  const auto path = test::MakeTempDir("pcap_us") / "us.pcap";
  PcapWriterOptions options;
  options.nanosecond_timestamps = false;
  {
    auto writer = PcapWriter::Create(path.string(), options, nullptr);
    ASSERT_NE(writer, nullptr);
    ASSERT_TRUE(writer->Write(5'000'001'999, 1, 2, Bytes{1, 2, 3}));
    EXPECT_FALSE(writer->Write(-1, 1, 2, Bytes{1}));
    EXPECT_FALSE(writer->Write(0, 1, 2, Bytes(PcapWriter::kMaxPayload + 1)));
  }
  EXPECT_EQ(bytes::ReadU32Le(ReadFile(path).data()), 0xA1B2C3D4u);  // classic µs magic
  std::vector<Bytes> got;
  const auto all = ReadAll(path, {}, &got);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].t_ns, 5'000'001'000);
}

TEST(PcapFile, ReadsCookedAndRawIpLinkTypes) {
  const auto dir = test::MakeTempDir("pcap_links");
  const Bytes payload = {9, 8, 7};
  const Bytes ip = Ipv4Udp(5, 2244, payload);
  Bytes sll(16 + ip.size(), 0);
  bytes::WriteU16Be(&sll[14], 0x0800);
  std::copy(ip.begin(), ip.end(), sll.begin() + 16);
  for (const auto& [linktype, record] :
       std::vector<std::pair<uint32_t, Bytes>>{{113, sll}, {101, ip}, {228, ip}}) {
    std::string name = "l";
    name += std::to_string(linktype);
    name += ".pcap";
    const auto path = dir / name;
    WriteFile(path, ClassicPcap(linktype, {record}));
    std::vector<Bytes> got;
    const auto all = ReadAll(path, {}, &got);
    ASSERT_EQ(all.size(), 1u) << "linktype " << linktype;
    EXPECT_EQ(got[0], payload);
    EXPECT_EQ(all[0].dst_port, 2244);
    EXPECT_EQ(all[0].t_ns, 100'000'250'000);
  }
}

TEST(PcapFile, ReadsPcapng) {
  // Section header, interface description (Ethernet, default µs resolution), enhanced packet.
  const Bytes frame = Ethernet(Ipv4Udp(7788, 7788, Bytes{0xA5, 0xFF}));
  Bytes f;
  auto u32 = [&f](uint32_t v) {
    f.resize(f.size() + 4);
    bytes::WriteU32Le(&f[f.size() - 4], v);
  };
  u32(0x0A0D0D0A), u32(28), u32(0x1A2B3C4D), u32(0x00000001), u32(0xFFFFFFFF), u32(0xFFFFFFFF),
      u32(28);
  u32(1), u32(20), u32(0x00000001), u32(65535), u32(20);  // link type 1, snaplen
  const uint32_t padded = static_cast<uint32_t>((frame.size() + 3) / 4 * 4);
  u32(6), u32(32 + padded), u32(0), u32(0), u32(1'000'000);  // t = 1 s
  u32(static_cast<uint32_t>(frame.size())), u32(static_cast<uint32_t>(frame.size()));
  f.insert(f.end(), frame.begin(), frame.end());
  f.resize(f.size() + (padded - frame.size()), 0);
  u32(32 + padded);
  const auto path = test::MakeTempDir("pcapng") / "x.pcapng";
  WriteFile(path, f);
  std::vector<Bytes> got;
  const auto all = ReadAll(path, {}, &got);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(got[0], (Bytes{0xA5, 0xFF}));
  EXPECT_EQ(all[0].t_ns, 1'000'000'000);
}

TEST(PcapFile, CountsMalformedNonUdpAndFragments) {
  Bytes truncated_ip = Ethernet(Ipv4Udp(1, 2, Bytes(50, 0)));
  truncated_ip.resize(truncated_ip.size() - 10);  // IP total length exceeds the capture
  Bytes fragment = Ethernet(Ipv4Udp(1, 2, Bytes{1}));
  bytes::WriteU16Be(&fragment[14 + 6], 0x2000);  // more fragments
  Bytes bad_udp_len = Ethernet(Ipv4Udp(1, 2, Bytes{1}));
  bytes::WriteU16Be(&bad_udp_len[14 + 24], 500);
  const std::vector<Bytes> records = {
      Ethernet(Ipv4Udp(1, 2, Bytes{42})),    // good
      Bytes{1, 2, 3},                        // shorter than Ethernet
      truncated_ip,                          // malformed
      Ethernet(Ipv4Udp(1, 2, Bytes{1}, 6)),  // TCP
      Ethernet(Bytes(40, 0), 0x86DD),        // IPv6
      fragment,
      bad_udp_len,
  };
  const auto path = test::MakeTempDir("pcap_bad") / "bad.pcap";
  WriteFile(path, ClassicPcap(1, records));
  std::vector<Bytes> got;
  PcapReadStats stats;
  std::string error;
  const auto all = ReadAll(path, {}, &got, &stats, &error);
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(got[0], Bytes{42});
  EXPECT_EQ(stats.records, 7u);
  EXPECT_EQ(stats.malformed, 3u);
  EXPECT_EQ(stats.not_udp, 2u);
  EXPECT_EQ(stats.fragments, 1u);
  EXPECT_TRUE(error.empty()) << error;
}

TEST(PcapFile, TruncatedFileEndsWithErrorAfterCompleteRecords) {
  const std::vector<Bytes> records(5, Ethernet(Ipv4Udp(1, 2, Bytes(100, 1))));
  Bytes file = ClassicPcap(1, records);
  file.resize(file.size() - 60);  // cut inside the last record
  const auto path = test::MakeTempDir("pcap_trunc") / "t.pcap";
  WriteFile(path, file);
  std::vector<Bytes> got;
  std::string error;
  const auto all = ReadAll(path, {}, &got, nullptr, &error);
  EXPECT_EQ(all.size(), 4u);
  EXPECT_FALSE(error.empty());
}

TEST(PcapFile, GarbageAndMissingFilesAreRejected) {
  std::mt19937 rng(7);
  Bytes garbage(4096);
  for (auto& b : garbage) b = static_cast<uint8_t>(rng());
  const auto dir = test::MakeTempDir("pcap_garbage");
  WriteFile(dir / "g.pcap", garbage);
  std::string error;
  EXPECT_EQ(PcapReader::Open((dir / "g.pcap").string(), {}, &error), nullptr);
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(PcapReader::Open((dir / "missing.pcap").string(), {}, &error), nullptr);
  EXPECT_EQ(PcapReader::OpenStream(nullptr, {}, &error), nullptr);
  EXPECT_EQ(PcapWriter::Create((dir / "no/such/dir.pcap").string(), {}, &error), nullptr);
}

TEST(PcapFile, OpensFromMemoryStream) {
  const Bytes file = ClassicPcap(1, {Ethernet(Ipv4Udp(3, 4, Bytes{5, 6}))});
  FILE* stream = fmemopen(const_cast<uint8_t*>(file.data()), file.size(), "rb");
  std::string error;
  auto reader = PcapReader::OpenStream(stream, {}, &error);
  ASSERT_NE(reader, nullptr) << error;
  UdpDatagram d;
  ASSERT_TRUE(reader->Next(&d));
  EXPECT_EQ(Bytes(d.payload.begin(), d.payload.end()), (Bytes{5, 6}));
  EXPECT_FALSE(reader->Next(&d));
}

TEST(PcapFile, RealRs16CaptureSplitsByPort) {
  SWLIO_REQUIRE_DATA(path, "rs16_washing_house/rs16_msop2244_difop7788.repackaged.pcap");
  std::vector<Bytes> msop, difop;
  PcapUdpFilter f_msop, f_difop;
  f_msop.dst_ports = {2244};
  f_difop.dst_ports = {7788};
  PcapReadStats stats;
  const auto m = ReadAll(path, f_msop, &msop, &stats);
  EXPECT_EQ(stats.records, 3040u);
  const auto d = ReadAll(path, f_difop, &difop);
  ASSERT_EQ(m.size(), 3000u);
  ASSERT_EQ(d.size(), 40u);
  for (const Bytes& p : msop) ASSERT_EQ(p.size(), 1248u);
  EXPECT_EQ(msop[0][0], 0x55);
  EXPECT_EQ(difop[0][0], 0xA5);
  EXPECT_EQ(m[0].src_ip, (std::array<uint8_t, 4>{192, 168, 1, 200}));
}

}  // namespace
}  // namespace swlio::drivers
