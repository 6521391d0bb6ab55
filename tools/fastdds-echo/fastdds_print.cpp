#include "fastdds_print.h"

#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "swlio/core/fnv1a.h"

namespace swlio::tools::fastdds_echo {
namespace {

void Bits(std::string& out, double v) {
  uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, " %016" PRIx64, bits);
  out += buffer;
}

void Text(std::string& out, const std::string& s) {
  static constexpr char kHex[] = "0123456789abcdef";
  out += " x";
  for (const char c : s) {
    const auto b = static_cast<unsigned char>(c);
    out += kHex[b >> 4];
    out += kHex[b & 15];
  }
}

void Header(std::string& out, const char* tag, const std_msgs::msg::dds_::Header_& h) {
  out += tag;
  out.append(" ").append(std::to_string(h.stamp().sec()));
  out.append(" ").append(std::to_string(h.stamp().nanosec()));
  Text(out, h.frame_id());
}

void PoseBits(std::string& out, const geometry_msgs::msg::dds_::Pose_& p) {
  for (double v : {p.position().x(), p.position().y(), p.position().z(), p.orientation().x(),
                   p.orientation().y(), p.orientation().z(), p.orientation().w()}) {
    Bits(out, v);
  }
}

void CovarianceBits(std::string& out, const std::array<double, 36>& c) {
  for (double v : c) Bits(out, v);
}

}  // namespace

std::string Line(const geometry_msgs::msg::dds_::PoseWithCovarianceStamped_& m) {
  std::string out;
  Header(out, "pose", m.header());
  PoseBits(out, m.pose().pose());
  CovarianceBits(out, m.pose().covariance());
  return out;
}

std::string Line(const nav_msgs::msg::dds_::Odometry_& m) {
  std::string out;
  Header(out, "odometry", m.header());
  Text(out, m.child_frame_id());
  PoseBits(out, m.pose().pose());
  CovarianceBits(out, m.pose().covariance());
  const auto& t = m.twist().twist();
  for (double v : {t.linear().x(), t.linear().y(), t.linear().z(), t.angular().x(), t.angular().y(),
                   t.angular().z()}) {
    Bits(out, v);
  }
  CovarianceBits(out, m.twist().covariance());
  return out;
}

std::string Line(const diagnostic_msgs::msg::dds_::DiagnosticArray_& m) {
  std::string out;
  Header(out, "health", m.header());
  out.append(" ").append(std::to_string(m.status().size()));
  for (const auto& s : m.status()) {
    out.append(" ").append(std::to_string(static_cast<unsigned>(s.level())));
    Text(out, s.name());
    Text(out, s.message());
    Text(out, s.hardware_id());
    out.append(" ").append(std::to_string(s.values().size()));
    for (const auto& kv : s.values()) {
      Text(out, kv.key());
      Text(out, kv.value());
    }
  }
  return out;
}

std::string Line(const nav_msgs::msg::dds_::Path_& m) {
  std::string out;
  Header(out, "path", m.header());
  out.append(" ").append(std::to_string(m.poses().size()));
  for (const auto& p : m.poses()) {
    out.append(" ").append(std::to_string(p.header().stamp().sec()));
    out.append(" ").append(std::to_string(p.header().stamp().nanosec()));
    Text(out, p.header().frame_id());
    PoseBits(out, p.pose());
  }
  return out;
}

std::string Line(const sensor_msgs::msg::dds_::PointCloud2_& m) {
  std::string out;
  Header(out, "map", m.header());
  for (const uint32_t v : {m.height(), m.width(), static_cast<uint32_t>(m.fields().size())}) {
    out.append(" ").append(std::to_string(v));
  }
  for (const auto& f : m.fields()) {
    Text(out, f.name());
    out.append(" ").append(std::to_string(f.offset()));
    out.append(" ").append(std::to_string(static_cast<unsigned>(f.datatype())));
    out.append(" ").append(std::to_string(f.count()));
  }
  out.append(" ").append(std::to_string(static_cast<unsigned>(m.is_bigendian())));
  out.append(" ").append(std::to_string(m.point_step()));
  out.append(" ").append(std::to_string(m.row_step()));
  out.append(" ").append(std::to_string(static_cast<unsigned>(m.is_dense())));
  out.append(" ").append(std::to_string(m.data().size()));
  const std::string_view bytes(reinterpret_cast<const char*>(m.data().data()), m.data().size());
  char digest[24];
  std::snprintf(digest, sizeof digest, " %016" PRIx64, Fnv1a64(bytes));
  out += digest;
  return out;
}

}  // namespace swlio::tools::fastdds_echo
