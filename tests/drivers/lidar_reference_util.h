#pragma once
// Test-only helpers for the RS-Helios-16P / VLP-16 reference comparisons: a minimal pcap record
// reader (libpcap, Ethernet/IPv4/UDP only) and readers for nebula's reference PCD files (ASCII
// and binary, fields x y z intensity return_type channel azimuth elevation distance time_stamp).
// The general pcap reader and scan assembler live elsewhere; this is just enough for the tests.

#include <pcap/pcap.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace swlio::test {

struct UdpRecord {
  int64_t t_ns = 0;  ///< pcap record time
  uint16_t dst_port = 0;
  std::vector<uint8_t> payload;
};

/// All UDP/IPv4 payloads of a classic or pcapng file, in file order. Empty on error.
inline std::vector<UdpRecord> ReadUdpRecords(const std::filesystem::path& path) {
  std::vector<UdpRecord> out;
  char err[PCAP_ERRBUF_SIZE] = {};
  pcap_t* pc = pcap_open_offline(path.c_str(), err);
  if (pc == nullptr) return out;
  pcap_pkthdr* hdr = nullptr;
  const u_char* data = nullptr;
  while (pcap_next_ex(pc, &hdr, &data) == 1) {
    const size_t n = hdr->caplen;
    if (n < 14 + 20 + 8 || data[12] != 0x08 || data[13] != 0x00) continue;  // IPv4 only
    const size_t ihl = static_cast<size_t>(data[14] & 0x0F) * 4;
    if (data[14 + 9] != 17 || n < 14 + ihl + 8) continue;  // UDP only
    const u_char* udp = data + 14 + ihl;
    UdpRecord r;
    r.t_ns = static_cast<int64_t>(hdr->ts.tv_sec) * 1'000'000'000 +
             static_cast<int64_t>(hdr->ts.tv_usec) * 1000;
    r.dst_port = static_cast<uint16_t>((udp[2] << 8) | udp[3]);
    const size_t udp_len = static_cast<size_t>((udp[4] << 8) | udp[5]);
    const size_t avail = n - 14 - ihl;
    const size_t len = udp_len >= 8 && udp_len <= avail ? udp_len - 8 : avail - 8;
    r.payload.assign(udp + 8, udp + 8 + len);
    out.push_back(std::move(r));
  }
  pcap_close(pc);
  return out;
}

struct RefPoint {
  float x = 0, y = 0, z = 0;
  uint8_t intensity = 0, return_type = 0;
  uint16_t channel = 0;
  float azimuth = 0, elevation = 0, distance = 0;
  uint32_t time_stamp = 0;
};

/// nebula's NebulaPoint PCD (SIZE 4 4 4 1 1 2 4 4 4 4), ASCII or binary. Empty on error.
inline std::vector<RefPoint> ReadNebulaPcd(const std::filesystem::path& path) {
  std::vector<RefPoint> pts;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  size_t n = 0;
  std::string data;
  while (std::getline(in, line)) {
    if (line.rfind("POINTS ", 0) == 0) n = std::stoul(line.substr(7));
    if (line.rfind("DATA ", 0) == 0) {
      data = line.substr(5);
      break;
    }
  }
  if (data == "ascii") {
    for (size_t i = 0; i < n && std::getline(in, line); ++i) {
      std::istringstream ss(line);
      RefPoint p;
      unsigned intensity = 0, rt = 0, ch = 0;
      ss >> p.x >> p.y >> p.z >> intensity >> rt >> ch >> p.azimuth >> p.elevation >> p.distance >>
          p.time_stamp;
      p.intensity = static_cast<uint8_t>(intensity);
      p.return_type = static_cast<uint8_t>(rt);
      p.channel = static_cast<uint16_t>(ch);
      pts.push_back(p);
    }
  } else if (data == "binary") {
    constexpr size_t kRecord = 32;
    std::vector<char> buf(n * kRecord);
    if (!in.read(buf.data(), static_cast<std::streamsize>(buf.size()))) return {};
    for (size_t i = 0; i < n; ++i) {
      const char* r = buf.data() + i * kRecord;
      RefPoint p;
      std::memcpy(&p.x, r, 4);
      std::memcpy(&p.y, r + 4, 4);
      std::memcpy(&p.z, r + 8, 4);
      p.intensity = static_cast<uint8_t>(r[12]);
      p.return_type = static_cast<uint8_t>(r[13]);
      std::memcpy(&p.channel, r + 14, 2);
      std::memcpy(&p.azimuth, r + 16, 4);
      std::memcpy(&p.elevation, r + 20, 4);
      std::memcpy(&p.distance, r + 24, 4);
      std::memcpy(&p.time_stamp, r + 28, 4);
      pts.push_back(p);
    }
  }
  return pts;
}

/// Distances between decoded points and a reference decoder's, against the tolerance of issue
/// 32: 1 cm + 0.025 % of the range.
struct DeviationStats {
  size_t count = 0;
  size_t within = 0;  ///< at most 1 cm + 0.025 % of range from the reference
  double median_m = 0.0;
  double max_m = 0.0;
  double Fraction() const {
    return count == 0 ? 0.0 : static_cast<double>(within) / static_cast<double>(count);
  }
};

inline bool WithinTolerance(double deviation_m, double range_m) {
  return deviation_m <= 0.01 + 0.00025 * range_m;
}

/// `deviation_m[i]` belongs to a return of range `range_m[i]`.
inline DeviationStats Summarize(std::vector<double> deviation_m,
                                const std::vector<double>& range_m) {
  DeviationStats s;
  s.count = deviation_m.size();
  for (size_t i = 0; i < s.count; ++i) s.within += WithinTolerance(deviation_m[i], range_m[i]);
  if (s.count == 0) return s;
  const auto middle = deviation_m.begin() + static_cast<std::ptrdiff_t>(s.count / 2);
  std::nth_element(deviation_m.begin(), middle, deviation_m.end());
  s.median_m = deviation_m[s.count / 2];
  s.max_m = *std::max_element(deviation_m.begin(), deviation_m.end());
  return s;
}

/// One line on stdout, so the figures show in the test log.
inline void Print(const char* what, const DeviationStats& s) {
  std::printf(
      "%s: %zu returns, %zu (%.3f %%) within 1 cm + 0.025 %% of range; median %.4f mm, "
      "max %.4f mm\n",
      what, s.count, s.within, 100.0 * s.Fraction(), s.median_m * 1e3, s.max_m * 1e3);
}

/// The reference PCDs in a directory, sorted by name (nebula names them by bag time, ns).
inline std::vector<std::filesystem::path> PcdFiles(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() == ".pcd") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace swlio::test
