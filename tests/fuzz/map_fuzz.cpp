// libFuzzer target for the saved map reader (saved_map.h, estimator/map-format.md): the input is
// the bytes of a map file. Whatever they hold, ReadSavedMap must return (no exception, no
// sanitizer report, no hang, no allocation beyond what the bytes justify) and its answer must
// be consistent. Any violated invariant is a bug (__builtin_trap).
//
// Each input is read twice: as given, and with its last 8 bytes replaced by the FNV-1a hash of
// the rest, so that mutations get past the checksum and reach the value checks (finite numbers,
// unit quaternions, increasing t_ns).
//
// Invariants:
// - a refusal says so: an error starting "map file: ";
// - an accepted map satisfies what the format promises (dimensions within the limits,
//   descriptor sizes rings × sectors, strictly increasing t_ns, rotations orthonormal) and
//   can be written back; reading that again gives the same map.
//
// Seeds: none needed (libFuzzer finds the magic and version from the comparisons); a small map
// written by the tests makes a good one.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "swlio/estimator/map/saved_map.h"

namespace {

using swlio::estimator::SavedMap;

void Check(bool ok) {
  if (!ok) __builtin_trap();
}

void Reseal(std::string* bytes) {
  if (bytes->size() < 8) return;
  const size_t body = bytes->size() - 8;
  uint64_t h = 0xcbf29ce484222325ULL;
  for (size_t i = 0; i < body; ++i)
    h = (h ^ static_cast<unsigned char>((*bytes)[i])) * 0x100000001b3ULL;
  for (size_t k = 0; k < 8; ++k) (*bytes)[body + k] = static_cast<char>((h >> (8 * k)) & 0xff);
}

bool IsRotation(const Eigen::Matrix3d& R) {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 && R.determinant() > 0;
}

void CheckPromises(const SavedMap& map) {
  Check(map.descriptor_rings >= 0 && map.descriptor_rings <= 1024);
  Check(map.descriptor_sectors >= 0 && map.descriptor_sectors <= 1024);
  const auto size = static_cast<size_t>(map.descriptor_rings * map.descriptor_sectors);
  for (size_t i = 0; i < map.nodes.size(); ++i) {
    const auto& node = map.nodes[i];
    Check(i == 0 || node.t_ns > map.nodes[i - 1].t_ns);
    Check(IsRotation(node.T_map_imu.linear()) && IsRotation(node.T_imu_lidar.linear()));
    Check(node.descriptor.size() == size);
    Check(node.planes_lidar.size() + node.edges_lidar.size() <= 1'000'000);
  }
}

bool SameMap(const SavedMap& a, const SavedMap& b) {
  if (a.descriptor_rings != b.descriptor_rings || a.descriptor_sectors != b.descriptor_sectors ||
      a.descriptor_max_range_m != b.descriptor_max_range_m ||
      a.descriptor_min_range_m != b.descriptor_min_range_m ||
      a.descriptor_height_offset_m != b.descriptor_height_offset_m ||
      a.nodes.size() != b.nodes.size()) {
    return false;
  }
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    const auto& x = a.nodes[i];
    const auto& y = b.nodes[i];
    const double pose_error =
        std::max((x.T_map_imu.matrix() - y.T_map_imu.matrix()).cwiseAbs().maxCoeff(),
                 (x.T_imu_lidar.matrix() - y.T_imu_lidar.matrix()).cwiseAbs().maxCoeff());
    // Translations may be huge: compare them relatively.
    const double scale = 1.0 + std::max(x.T_map_imu.translation().cwiseAbs().maxCoeff(),
                                        x.T_imu_lidar.translation().cwiseAbs().maxCoeff());
    if (x.t_ns != y.t_ns || !(pose_error <= 1e-12 * scale) || x.planes_lidar != y.planes_lidar ||
        x.edges_lidar != y.edges_lidar || x.descriptor != y.descriptor) {
      return false;
    }
  }
  return true;
}

void ReadOne(const std::string& bytes) {
  std::istringstream in(bytes);
  std::string error;
  const auto map = swlio::estimator::ReadSavedMap(in, &error);
  if (!map) {
    Check(error.rfind("map file: ", 0) == 0 && error.size() > 10);
    return;
  }
  CheckPromises(*map);
  std::ostringstream out;
  Check(swlio::estimator::WriteSavedMap(out, *map, &error));
  std::istringstream again(out.str());
  const auto reread = swlio::estimator::ReadSavedMap(again, &error);
  Check(reread.has_value() && SameMap(*map, *reread));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  ReadOne(bytes);
  Reseal(&bytes);
  ReadOne(bytes);
  return 0;
}
