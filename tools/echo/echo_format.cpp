#include "echo_format.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <limits>

#include "swlio/ipc/point_cloud.h"

namespace swlio::tools::echo {
namespace {

// Built by appending: GCC 12 reports a false -Wrestrict for `"literal" + std::string&&`.
template <size_t N>
void AppendVector(std::string& out, const std::array<double, N>& v) {
  out += '[';
  for (size_t i = 0; i < N; ++i) {
    if (i > 0) out += ' ';
    out += FormatDouble(v[i]);
  }
  out += ']';
}

void AppendPose(std::string& out, const char* prefix, const ipc::Pose& pose) {
  out.append(" ").append(prefix).append("p=");
  AppendVector(out, pose.position_m);
  out.append(" ").append(prefix).append("q=");
  AppendVector(out, pose.orientation_xyzw);
}

/// Variances on the covariance diagonal (x y z roll pitch yaw).
void AppendVariances(std::string& out, const ipc::Covariance6& c) {
  std::array<double, 6> diagonal{};
  for (size_t i = 0; i < 6; ++i) diagonal[i] = c[i * 6 + i];
  out += " var=";
  AppendVector(out, diagonal);
}

void AppendHeader(std::string& out, const char* tag, int64_t t_ns, const std::string& frame) {
  out.append(tag).append(" t=").append(FormatStamp(t_ns)).append(" frame=").append(frame);
}

const char* LevelName(ipc::DiagnosticLevel level) {
  switch (level) {
    case ipc::DiagnosticLevel::kOk:
      return "OK";
    case ipc::DiagnosticLevel::kWarn:
      return "WARN";
    case ipc::DiagnosticLevel::kError:
      return "ERROR";
    case ipc::DiagnosticLevel::kStale:
      return "STALE";
  }
  return "?";
}

}  // namespace

std::string FormatStamp(int64_t t_ns) {
  // Sign and magnitude: a decimal "-1.5" is -(1 + 0.5), not floor(-1.5) + 0.5.
  const uint64_t magnitude =
      t_ns < 0 ? ~static_cast<uint64_t>(t_ns) + 1u : static_cast<uint64_t>(t_ns);
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%s%llu.%09llu", t_ns < 0 ? "-" : "",
                static_cast<unsigned long long>(magnitude / 1'000'000'000u),
                static_cast<unsigned long long>(magnitude % 1'000'000'000u));
  return buffer;
}

std::string FormatDouble(double v) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

std::string FormatLine(const ipc::PoseWithCovarianceStamped& m) {
  std::string out;
  AppendHeader(out, "pose", m.t_ns, m.frame_id);
  AppendPose(out, "", m.pose);
  AppendVariances(out, m.covariance);
  return out;
}

std::string FormatLine(const ipc::Odometry& m) {
  std::string out;
  AppendHeader(out, "odometry", m.t_ns, m.frame_id);
  out.append(" child=").append(m.child_frame_id);
  AppendPose(out, "", m.pose);
  out += " v=";
  AppendVector(out, m.twist.linear_mps);
  out += " w=";
  AppendVector(out, m.twist.angular_radps);
  return out;
}

std::string FormatLine(const ipc::TFMessage& m) {
  std::string out = "tf n=" + std::to_string(m.transforms.size());
  for (const ipc::TransformStamped& t : m.transforms) {
    out.append(" | ").append(t.frame_id).append(" -> ").append(t.child_frame_id);
    out.append(" t=").append(FormatStamp(t.t_ns)).append(" p=");
    AppendVector(out, t.transform.translation_m);
    out += " q=";
    AppendVector(out, t.transform.rotation_xyzw);
  }
  return out;
}

std::string FormatLine(const ipc::DiagnosticArray& m) {
  std::string out;
  out.append("health t=").append(FormatStamp(m.t_ns)).append(" n=");
  out += std::to_string(m.status.size());
  for (const auto& s : m.status) {
    out.append(" | ").append(s.name).append(" ").append(LevelName(s.level));
    out.append(" \"").append(s.message).append("\"");
    for (const auto& kv : s.values) out.append(" ").append(kv.key).append("=").append(kv.value);
  }
  return out;
}

std::string FormatLine(const ipc::Path& m) {
  std::string out;
  AppendHeader(out, "path", m.t_ns, m.frame_id);
  out.append(" poses=").append(std::to_string(m.poses.size()));
  if (!m.poses.empty()) {
    out.append(" last_t=").append(FormatStamp(m.poses.back().t_ns));
    AppendPose(out, "last_", m.poses.back().pose);
  }
  return out;
}

std::string FormatLine(const ipc::PointCloud2& m) {
  std::string out;
  AppendHeader(out, "map", m.t_ns, m.frame_id);
  const uint64_t points = uint64_t{m.width} * m.height;
  out.append(" points=").append(std::to_string(points));
  out.append(" (").append(std::to_string(m.width)).append("x");
  out.append(std::to_string(m.height)).append(")");
  out.append(" bytes=").append(std::to_string(m.data.size()));
  out.append(" point_step=").append(std::to_string(m.point_step));
  out.append(" fields=");
  for (size_t i = 0; i < m.fields.size(); ++i)
    out.append(i > 0 ? "," : "").append(m.fields[i].name);
  if (points == 0 || !ipc::HasXyzLayout(m)) return out;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::array<double, 3> lo = {kInf, kInf, kInf};
  std::array<double, 3> hi = {-kInf, -kInf, -kInf};
  for (size_t i = 0; i < points; ++i) {
    const std::array<float, 3> p = ipc::XyzAt(m, i);
    for (size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], static_cast<double>(p[a]));
      hi[a] = std::max(hi[a], static_cast<double>(p[a]));
    }
  }
  out += " min=";
  AppendVector(out, lo);
  out += " max=";
  AppendVector(out, hi);
  return out;
}

std::string TumLine(int64_t t_ns, const ipc::Pose& pose) {
  std::string out = FormatStamp(t_ns);
  for (double v : pose.position_m) out.append(" ").append(FormatDouble(v));
  for (double v : pose.orientation_xyzw) out.append(" ").append(FormatDouble(v));
  return out;
}

}  // namespace swlio::tools::echo
