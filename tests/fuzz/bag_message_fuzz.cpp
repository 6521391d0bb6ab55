// libFuzzer target: the message decoders (CDR and ROS 1) and the PointCloud2 conversion.
// Input: one selector byte (low 4 bits: the kind, RosMessageKind order; bit 7: ROS 1 instead of
// CDR), then one serialized message. Invariants: packet payloads lie inside the input; cloud
// points are finite with dt_ns ≥ 0 and t_start ≤ t_end.
// Seeds: tests/fuzz/corpus/bag_message and, in scripts/fuzz, messages of the real bags.

#include <cmath>
#include <string>

#include "bag_fuzz_checks.h"

namespace swlio::fuzz {
namespace {

namespace bag = drivers::bag;

void CheckPackets(const bag::LidarPacketsMsg& m, const uint8_t* data, size_t size) {
  for (const bag::LidarPacketView& p : m.packets) {
    Check(p.payload.empty() ||
          (p.payload.data() >= data && p.payload.data() + p.payload.size() <= data + size));
  }
}

void CheckCloud(const bag::PointCloud2Msg& msg) {
  bag::CloudPoints cloud;
  std::string error;
  if (!bag::CloudFromPointCloud2(msg, {}, &cloud, &error)) return;
  Check(cloud.scan.t_start_ns <= cloud.scan.t_end_ns);
  Check(cloud.scan.points.size() + cloud.non_finite_points == cloud.points_in);
  for (const auto& p : cloud.scan.points) {
    Check(p.dt_ns >= 0 && std::isfinite(p.xyz_m.x()) && std::isfinite(p.xyz_m.y()) &&
          std::isfinite(p.xyz_m.z()));
  }
}

}  // namespace

int FuzzBagMessage(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const auto kind = static_cast<bag::RosMessageKind>(data[0] & 0x0F);
  if (static_cast<uint8_t>(kind) > static_cast<uint8_t>(bag::RosMessageKind::kTwistStamped)) {
    return 0;
  }
  const auto encoding =
      (data[0] & 0x80) != 0 ? bag::MessageEncoding::kRos1 : bag::MessageEncoding::kCdr;
  bag::DecodedMessage d;
  std::string error;
  if (!bag::DecodeMessage(kind, encoding, {data + 1, size - 1}, &d, &error)) {
    Check(!error.empty());
    return 0;
  }
  CheckPackets(d.packets, data, size);
  if (d.kind == bag::RosMessageKind::kPointCloud2) CheckCloud(d.cloud);
  return 0;
}

}  // namespace swlio::fuzz

#ifndef SWLIO_FUZZ_NO_MAIN
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return swlio::fuzz::FuzzBagMessage(data, size);
}
#endif
