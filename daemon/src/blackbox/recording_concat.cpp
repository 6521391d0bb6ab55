#include "swlio/daemon/blackbox/recording_concat.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

namespace swlio::daemon {
namespace {

constexpr std::streamsize kChunk = 1 << 20;
constexpr std::streamoff kPcapGlobalHeader = 24;  // libpcap file format: the global header

struct Joiner {
  const std::vector<std::filesystem::path>& parts;
  const std::filesystem::path& out;
  const std::function<void()>& progress;
  std::string* error;

  bool Fail(const std::string& what) {
    *error = what + (errno != 0 ? std::string(": ") + std::strerror(errno) : "");
    return false;
  }

  /// Appends `in` from `skip` bytes on to `dst`.
  bool Copy(std::ifstream& in, std::streamoff skip, std::ofstream& dst, const std::string& name) {
    in.seekg(skip);
    std::string buffer(static_cast<size_t>(kChunk), '\0');
    while (in) {
      in.read(buffer.data(), kChunk);
      const std::streamsize n = in.gcount();
      if (n <= 0) break;
      if (!dst.write(buffer.data(), n)) return Fail("cannot write " + (out / name).string());
      if (progress) progress();
    }
    return true;
  }

  /// Every part's `name` after each other; `skip` bytes of every part but the first. Missing
  /// files are skipped (can.log exists only with CAN).
  bool Binary(const std::string& name, std::streamoff skip) {
    std::ofstream dst;
    bool first = true;
    for (const std::filesystem::path& p : parts) {
      std::ifstream in(p / name, std::ios::binary);
      if (!in) continue;
      if (!dst.is_open()) dst.open(out / name, std::ios::binary);
      if (!dst) return Fail("cannot create " + (out / name).string());
      if (!Copy(in, first ? 0 : skip, dst, name)) return false;
      first = false;
    }
    return !dst.is_open() || dst.flush() ? true : Fail("cannot write " + (out / name).string());
  }

  /// Text files with one header line: the first part's header, every part's rows.
  bool Csv(const std::string& name) {
    std::ofstream dst;
    bool header = false;
    for (const std::filesystem::path& p : parts) {
      std::ifstream in(p / name);
      std::string line;
      if (!in || !std::getline(in, line)) continue;
      if (!dst.is_open()) dst.open(out / name);
      if (!header) dst << line << '\n';
      header = true;
      if (!Copy(in, in.tellg(), dst, name)) return false;
    }
    return !dst.is_open() || dst.flush() ? true : Fail("cannot write " + (out / name).string());
  }

  /// imu.rx.csv: `byte_offset,bytes,t_rx_ns` rows, offsets moved on by the bytes of imu.xbus in
  /// the parts before.
  bool SerialIndex() {
    std::ofstream dst(out / "imu.rx.csv");
    dst << "byte_offset,bytes,t_rx_ns\n";
    uint64_t base = 0;
    for (const std::filesystem::path& p : parts) {
      std::ifstream in(p / "imu.rx.csv");
      std::string line;
      std::getline(in, line);  // header
      while (std::getline(in, line)) {
        unsigned long long offset = 0;
        const size_t comma = line.find(',');
        if (comma == std::string::npos) continue;
        std::istringstream(line.substr(0, comma)) >> offset;
        dst << (base + offset) << line.substr(comma) << '\n';
      }
      std::error_code ec;
      const uintmax_t n = std::filesystem::file_size(p / "imu.xbus", ec);
      base += ec ? 0 : n;
      if (progress) progress();
    }
    return dst.flush() ? true : Fail("cannot write " + (out / "imu.rx.csv").string());
  }

  bool First(const std::string& name) {
    std::error_code ec;
    std::filesystem::copy_file(parts.front() / name, out / name, ec);
    if (ec && std::filesystem::exists(parts.front() / name))
      return Fail("cannot copy " + name + ": " + ec.message());
    return true;
  }
};

}  // namespace

bool ConcatenateRecordings(const std::vector<std::filesystem::path>& parts,
                           const std::filesystem::path& out,
                           const std::function<void()>& progress,
                           std::string* error) {
  errno = 0;
  if (parts.empty()) return *error = "no recording to join", false;
  std::error_code ec;
  if (!std::filesystem::create_directories(out, ec)) {
    *error = "cannot create " + out.string() + (ec ? ": " + ec.message() : ": it exists");
    return false;
  }
  Joiner j{parts, out, progress, error};
  return j.First("manifest.yaml") && j.First("config.yaml") &&
         j.Binary("lidar.pcap", kPcapGlobalHeader) && j.Binary("imu.xbus", 0) && j.SerialIndex() &&
         j.Binary("can.log", 0) && j.Csv("clock_offsets.csv") && j.Csv("health.csv") &&
         j.Binary("log.txt", 0) && j.Binary("odometry.tum", 0);
}

}  // namespace swlio::daemon
