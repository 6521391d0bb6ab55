// A recording's manifest.yaml, read line by line for the facts a replay needs (time base, ports,
// the rig). Deliberately not YAML: the daemon recorder and the simulator write these lines
// themselves, one key per line; a key inside a block (`wheel:`, `gnss:`) is looked for only in
// that block's indented lines, so blocks may reuse short keys such as `rate_hz`.

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>

#include "swlio/daemon/recording/recording_reader.h"
#include "swlio/drivers/recording_format.h"

namespace swlio::daemon {
namespace {

constexpr double kPi = std::numbers::pi;

/// Calls `fn(line)` for every indented line of the top-level block `block`.
template <typename Fn>
void ForEachLineIn(const std::filesystem::path& dir, std::string_view block, Fn fn) {
  std::ifstream in(dir / "manifest.yaml");
  const std::string header = std::string(block) + ":";
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line[0] != ' ') {
      inside = line.compare(0, header.size(), header) == 0;
      continue;
    }
    if (inside) fn(line);
  }
}

bool AllFinite(std::initializer_list<double> values) {
  for (const double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

/// The manifest's top-level `key: value` line as text ("" when absent).
std::string TopLevelValue(const std::filesystem::path& dir, const std::string& key) {
  std::ifstream in(dir / "manifest.yaml");
  const std::string prefix = key + ": ";
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, prefix.size(), prefix) == 0) return line.substr(prefix.size());
  }
  return "";
}

/// What to do with a version-1 recording: re-simulate it, or for a swliod recording the same
/// extrinsic in the new frame. Points in the manual frame are Rz(+90°) of the vendor frame's
/// (x_manual = −y, y_manual = x), so T_imu_lidar's rotation becomes R·Rz(+90°), its
/// translation unchanged (tests/daemon/recording/recording_version_test.cpp checks the sign).
std::string Version1Advice(const std::filesystem::path& dir) {
  const std::string mode = TopLevelValue(dir, "mode");
  if (mode == "file" || mode == "live") {
    return "write it again with this swlio-sim (same --scenario, --seed and --duration): the "
           "simulator now also casts its rays from the lens centre the decoder adds";
  }
  const std::optional<Eigen::Isometry3d> T = ManifestExtrinsic(dir);
  if (!T) return "record it again";
  const Eigen::Quaterniond q(T->linear() * Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()));
  char text[192];
  std::snprintf(text, sizeof text, "[%.17g, %.17g, %.17g, %.17g]", q.x(), q.y(), q.z(), q.w());
  return std::string("the same extrinsic in the new frame is quaternion_xyzw: ") + text +
         " (R·Rz(+90°), translation unchanged): put that line and format_version: 2 into its "
         "manifest.yaml, or record it again";
}

}  // namespace

std::string ManifestVersionProblem(const std::filesystem::path& dir) {
  const std::filesystem::path manifest = dir / "manifest.yaml";
  if (!std::ifstream(manifest)) {
    return "cannot read " + manifest.string() + " (a recording folder states its format there)";
  }
  const std::string text = TopLevelValue(dir, "format_version");
  if (text.empty()) {
    return manifest.string() + ": no format_version line (swliod --record and swlio-sim write one)";
  }
  const long long version = std::atoll(text.c_str());
  const long long current = drivers::kRecordingFormatVersion;
  if (version == current) return "";
  const std::string head = manifest.string() + ": format_version " + text +
                           ", this program reads " + std::to_string(current) + ": ";
  if (version == 1) {
    return head +
           "recorded before swlio decoded LiDAR points in the vendor driver's frame (x forward, "
           "y left, z up, with the lens offset; issue 32), so its extrinsic is for the RoboSense "
           "manual's frame (y forward, x right) and would be misread. To use it, " +
           Version1Advice(dir);
  }
  if (version > current) return head + "written by a newer swlio; read it with that one";
  return head + "not a format_version this program knows";
}

TimeScale ManifestTimeScale(const std::filesystem::path& dir) {
  std::ifstream in(dir / "manifest.yaml");
  std::string line;
  TimeScale t;
  double scale = 0.0;
  long long origin = 0;
  while (std::getline(in, line)) {
    if (std::sscanf(line.c_str(), "time_scale: %lf", &scale) == 1 && scale > 0.0) t.scale = scale;
    if (std::sscanf(line.c_str(), "time_origin_ns: %lld", &origin) == 1) t.origin_ns = origin;
  }
  return t;
}

drivers::LidarConfig WithManifestPorts(const std::filesystem::path& dir,
                                       drivers::LidarConfig lidar) {
  std::ifstream in(dir / "manifest.yaml");
  std::string line;
  unsigned port = 0;
  while (std::getline(in, line)) {
    if (std::sscanf(line.c_str(), " msop_port: %u", &port) == 1 && port <= 65535)
      lidar.msop_port = static_cast<uint16_t>(port);
    if (std::sscanf(line.c_str(), " difop_port: %u", &port) == 1 && port <= 65535)
      lidar.difop_port = static_cast<uint16_t>(port);
  }
  return lidar;
}

std::optional<Eigen::Isometry3d> ManifestExtrinsic(const std::filesystem::path& dir) {
  std::ifstream in(dir / "manifest.yaml");
  std::string line;
  double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1};
  int found = 0;
  while (std::getline(in, line)) {
    found += std::sscanf(line.c_str(), " translation_m: [%lf, %lf, %lf]", &t[0], &t[1], &t[2]) == 3;
    found += std::sscanf(line.c_str(), " quaternion_xyzw: [%lf, %lf, %lf, %lf]", &q[0], &q[1],
                         &q[2], &q[3]) == 4;
  }
  if (found != 2) return std::nullopt;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
  return T;
}

std::optional<Eigen::Isometry3d> ManifestWheelExtrinsic(const std::filesystem::path& dir) {
  double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1};
  bool have_t = false, have_q = false;
  ForEachLineIn(dir, "wheel", [&](const std::string& line) {
    const char* l = line.c_str();
    have_t |=
        std::sscanf(l, " T_imu_base_translation_m: [%lf, %lf, %lf]", &t[0], &t[1], &t[2]) == 3;
    have_q |= std::sscanf(l, " T_imu_base_quaternion_xyzw: [%lf, %lf, %lf, %lf]", &q[0], &q[1],
                          &q[2], &q[3]) == 4;
  });
  const Eigen::Quaterniond quat(q[3], q[0], q[1], q[2]);
  if (!have_t || !have_q || !AllFinite({t[0], t[1], t[2], q[0], q[1], q[2], q[3]}) ||
      quat.norm() < 0.5) {
    return std::nullopt;
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = quat.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
  return T;
}

std::optional<drivers::CanConfig> ManifestWheelCan(const std::filesystem::path& dir) {
  int id = -1, dlc = -1, left = -1, right = -1;
  double scale = 0.0, track_m = 0.0;
  char mode[32] = {}, unit[32] = {};
  ForEachLineIn(dir, "wheel", [&](const std::string& line) {
    const char* l = line.c_str();
    std::sscanf(l, " can_mode: %31s", mode);
    std::sscanf(l, " can_wheel_speed_unit: %31s", unit);
    std::sscanf(l, " can_frame_id: %i", &id);
    std::sscanf(l, " can_dlc: %i", &dlc);
    std::sscanf(l, " can_left_byte_offset: %i", &left);
    std::sscanf(l, " can_right_byte_offset: %i", &right);
    std::sscanf(l, " can_scale_mps_per_lsb: %lf", &scale);
    std::sscanf(l, " track_width_m: %lf", &track_m);
  });
  if (std::string_view(mode) != "wheel_speeds" || std::string_view(unit) != "mps") {
    return std::nullopt;
  }
  drivers::CanConfig c;
  c.enabled = true;
  c.mode = "wheel_speeds";
  c.wheel_speed_unit = "mps";
  c.track_width_m = track_m;
  using Field = std::pair<const char*, int>;
  for (const auto& [role, offset] :
       std::array<Field, 2>{Field{"left_wheel_speed", left}, Field{"right_wheel_speed", right}}) {
    drivers::CanSignalConfig s;
    s.role = role;
    s.can_id = id;
    s.byte_offset = offset;
    s.length_bits = 16;
    s.byte_order = "intel";
    s.is_signed = true;
    s.scale = scale;
    s.dlc = dlc;
    c.signals.push_back(s);
  }
  if (!c.ValidateLayout().empty()) return std::nullopt;
  return c;
}

std::optional<ManifestGnss> ManifestGnssSetup(const std::filesystem::path& dir) {
  ManifestGnss g;
  double b[3] = {0, 0, 0};
  int found = 0;
  ForEachLineIn(dir, "gnss", [&](const std::string& line) {
    const char* l = line.c_str();
    found |= std::sscanf(l, " origin_lat_deg: %lf", &g.origin.lat_deg) == 1 ? 1 : 0;
    found |= std::sscanf(l, " origin_lon_deg: %lf", &g.origin.lon_deg) == 1 ? 2 : 0;
    found |= std::sscanf(l, " origin_height_m: %lf", &g.origin.height_m) == 1 ? 4 : 0;
    found |= std::sscanf(l, " antenna_imu_m: [%lf, %lf, %lf]", &b[0], &b[1], &b[2]) == 3 ? 8 : 0;
    std::sscanf(l, " rate_hz: %lf", &g.rate_hz);
    std::sscanf(l, " sigma_h_m: %lf", &g.sigma_h_m);
    std::sscanf(l, " sigma_v_m: %lf", &g.sigma_v_m);
  });
  const Geodetic& o = g.origin;
  if (found != 15 || !AllFinite({o.lat_deg, o.lon_deg, o.height_m, b[0], b[1], b[2]}) ||
      std::abs(o.lat_deg) > 90.0 || std::abs(o.lon_deg) > 180.0) {
    return std::nullopt;
  }
  g.antenna_imu_m = Eigen::Vector3d(b[0], b[1], b[2]);
  return g;
}

}  // namespace swlio::daemon
