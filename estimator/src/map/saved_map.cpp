#include "swlio/estimator/map/saved_map.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <ostream>
#include <string_view>
#include <system_error>

#include "swlio/core/fnv1a.h"
#include "swlio/estimator/common/replace_file.h"

namespace swlio::estimator {
namespace {

constexpr std::string_view kMagic = "SWLIOMAP";
constexpr size_t kHeaderBytes = 52;
constexpr size_t kNodeFixedBytes = 128;
constexpr size_t kPointBytes = 12;
constexpr size_t kChecksumBytes = 8;

std::string Hex(uint64_t v) {
  std::string s = "0x";
  for (int shift = 60; shift >= 0; shift -= 4) s += "0123456789abcdef"[(v >> shift) & 0xf];
  return s;
}

/// Little-endian fields read byte by byte (never a struct cast over the buffer). Reading past
/// the end yields zero bytes; callers check the layout before they read.
class Cursor {
 public:
  Cursor(std::string_view bytes, size_t offset)
      : bytes_(bytes), offset_(std::min(offset, bytes.size())) {}
  size_t offset() const { return offset_; }
  size_t remaining() const { return bytes_.size() - offset_; }
  void Skip(size_t n) { offset_ += std::min(n, remaining()); }
  uint32_t U32() { return static_cast<uint32_t>(Uint(4)); }
  uint64_t U64() { return Uint(8); }
  int64_t I64() { return static_cast<int64_t>(Uint(8)); }
  double F64() { return std::bit_cast<double>(Uint(8)); }
  float F32() { return std::bit_cast<float>(U32()); }

 private:
  uint64_t Uint(int n) {
    uint64_t v = 0;
    for (int k = 0; k < n && offset_ < bytes_.size(); ++k) {
      v |= uint64_t{static_cast<unsigned char>(bytes_[offset_++])} << (8 * k);
    }
    return v;
  }
  std::string_view bytes_;
  size_t offset_;
};

/// Little-endian fields into a stream through a buffer, hashing everything written; Finish()
/// appends the hash.
class Writer {
 public:
  explicit Writer(std::ostream& out) : out_(out) { buffer_.reserve(kFlushBytes + 64); }
  void Bytes(std::string_view b) { buffer_.append(b); }
  void U32(uint32_t v) { Uint(v, 4); }
  void I64(int64_t v) { Uint(static_cast<uint64_t>(v), 8); }
  void F64(double v) { Uint(std::bit_cast<uint64_t>(v), 8); }
  void F32(float v) { Uint(std::bit_cast<uint32_t>(v), 4); }
  bool Finish() {
    Flush();
    Uint(hash_, 8);
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    out_.flush();
    return out_.good();
  }

 private:
  static constexpr size_t kFlushBytes = size_t{1} << 16;
  void Uint(uint64_t v, int n) {
    for (int k = 0; k < n; ++k) buffer_.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
    if (buffer_.size() >= kFlushBytes) Flush();
  }
  void Flush() {
    hash_ = Fnv1a64(buffer_, hash_);
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }
  std::ostream& out_;
  std::string buffer_;
  uint64_t hash_ = kFnv1a64OffsetBasis;
};

struct Header {
  uint32_t version = 0;
  uint32_t rings = 0;
  uint32_t sectors = 0;
  double max_range_m = 0.0;
  double min_range_m = 0.0;
  double height_offset_m = 0.0;
  uint32_t nodes = 0;
};

void SetError(std::string* error, std::string message) {
  if (error != nullptr) *error = std::move(message);
}

std::string Node(size_t i, size_t offset) {
  return "node " + std::to_string(i) + " (at byte " + std::to_string(offset) + "): ";
}

// The descriptor settings' rules, shared by the writer and the reader.
std::string DescriptorIssue(
    uint64_t rings, uint64_t sectors, double max_m, double min_m, double h_m) {
  if (rings > kSavedMapMaxDescriptorDim || sectors > kSavedMapMaxDescriptorDim) {
    return "descriptor " + std::to_string(rings) + "x" + std::to_string(sectors) +
           " beyond the limit of " + std::to_string(kSavedMapMaxDescriptorDim) + " per dimension";
  }
  if ((rings == 0) != (sectors == 0)) {
    return "descriptor " + std::to_string(rings) + "x" + std::to_string(sectors) +
           ": rings and sectors must both be 0 or both be positive";
  }
  if (!std::isfinite(max_m) || !std::isfinite(min_m) || !std::isfinite(h_m)) {
    return "descriptor ranges or height offset not finite";
  }
  if (rings > 0 && !(min_m >= 0.0 && min_m < max_m)) {
    return "descriptor ranges need 0 <= min < max (min " + std::to_string(min_m) + " m, max " +
           std::to_string(max_m) + " m)";
  }
  return {};
}

// ---------------------------------------------------------------------------------------------
// Writing.

bool IsRotation(const Eigen::Matrix3d& R) {
  return R.allFinite() && (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() <= 1e-6 &&
         R.determinant() > 0.0;
}

bool FitsFloat(const Eigen::Vector3d& p) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return p.allFinite() && p.cwiseAbs().maxCoeff() <= kMax;
}

std::string NodeIssue(const SavedMapNode& node, size_t descriptor_size) {
  if (!node.T_map_imu.translation().allFinite() || !IsRotation(node.T_map_imu.linear())) {
    return "T_map_imu is not a finite rigid transform";
  }
  if (!node.T_imu_lidar.translation().allFinite() || !IsRotation(node.T_imu_lidar.linear())) {
    return "T_imu_lidar is not a finite rigid transform";
  }
  if (node.planes_lidar.size() + node.edges_lidar.size() > kSavedMapMaxPointsPerNode) {
    return "more than " + std::to_string(kSavedMapMaxPointsPerNode) + " points";
  }
  for (const auto* points : {&node.planes_lidar, &node.edges_lidar}) {
    if (!std::all_of(points->begin(), points->end(), FitsFloat)) {
      return "a point is not finite or beyond float range";
    }
  }
  if (node.descriptor.size() != descriptor_size) {
    return "descriptor has " + std::to_string(node.descriptor.size()) + " values, the map's " +
           "dimensions need " + std::to_string(descriptor_size);
  }
  for (float v : node.descriptor) {
    if (!std::isfinite(v)) return "descriptor value not finite";
  }
  return {};
}

std::string MapIssue(const SavedMap& map) {
  if (map.descriptor_rings < 0 || map.descriptor_sectors < 0) return "negative descriptor size";
  const auto rings = static_cast<uint64_t>(map.descriptor_rings);
  const auto sectors = static_cast<uint64_t>(map.descriptor_sectors);
  std::string issue = DescriptorIssue(rings, sectors, map.descriptor_max_range_m,
                                      map.descriptor_min_range_m, map.descriptor_height_offset_m);
  if (!issue.empty()) return issue;
  if (map.nodes.size() > kSavedMapMaxNodes) {
    return std::to_string(map.nodes.size()) + " nodes, beyond the limit of " +
           std::to_string(kSavedMapMaxNodes);
  }
  for (size_t i = 0; i < map.nodes.size(); ++i) {
    if (i > 0 && map.nodes[i].t_ns <= map.nodes[i - 1].t_ns) {
      return "node " + std::to_string(i) + ": t_ns not after the previous node's";
    }
    issue = NodeIssue(map.nodes[i], static_cast<size_t>(rings * sectors));
    if (!issue.empty()) return "node " + std::to_string(i) + ": " + issue;
  }
  return {};
}

void PutPose(Writer& w, const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(T.linear()).normalized();
  for (int k = 0; k < 3; ++k) w.F64(T.translation()[k]);
  for (double v : {q.x(), q.y(), q.z(), q.w()}) w.F64(v);
}

void PutPoints(Writer& w, const std::vector<Eigen::Vector3d>& points) {
  for (const auto& p : points) {
    for (int k = 0; k < 3; ++k) w.F32(static_cast<float>(p[k]));
  }
}

// ---------------------------------------------------------------------------------------------
// Reading: the whole stream into memory, then the layout (every count against the limits and
// the bytes left), the checksum, and only then the values.

// Chunk by chunk, so that memory follows the bytes that arrive; `expected_bytes` (a file's
// size) only saves the regrowing.
bool ReadAll(std::istream& in, size_t expected_bytes, std::string* bytes, std::string* why) {
  constexpr size_t kChunk = size_t{1} << 16;
  bytes->reserve(expected_bytes + 1);
  while (in) {
    const size_t old = bytes->size();
    bytes->resize(old + kChunk);
    in.read(bytes->data() + old, static_cast<std::streamsize>(kChunk));
    bytes->resize(old + static_cast<size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  }
  if (in.bad()) {
    *why = "read error after " + std::to_string(bytes->size()) + " bytes";
    return false;
  }
  return true;
}

std::optional<Header> ParseHeader(std::string_view bytes, std::string* why) {
  if (bytes.substr(0, kMagic.size()) != kMagic.substr(0, std::min(bytes.size(), kMagic.size()))) {
    *why = "bad magic (not a swlio map: the file must start with \"SWLIOMAP\")";
    return std::nullopt;
  }
  const std::string truncated = "truncated header: " + std::to_string(bytes.size()) + " of " +
                                std::to_string(kHeaderBytes) + " bytes";
  if (bytes.size() < kMagic.size() + 4) {
    *why = truncated;
    return std::nullopt;
  }
  Cursor c(bytes, kMagic.size());
  const uint32_t version = c.U32();
  if (version != kSavedMapVersion && version != kSavedMapVersionManualFrame) {
    *why = "unsupported version " + std::to_string(version) + " (this reader knows versions " +
           std::to_string(kSavedMapVersionManualFrame) + " and " +
           std::to_string(kSavedMapVersion) + ")";
    return std::nullopt;
  }
  if (bytes.size() < kHeaderBytes) {
    *why = truncated;
    return std::nullopt;
  }
  const uint32_t flags = c.U32();
  if (flags != 0) {
    *why = "unsupported header flags " + std::to_string(flags) + " (no flag is defined)";
    return std::nullopt;
  }
  Header h;
  h.version = version;
  h.rings = c.U32();
  h.sectors = c.U32();
  h.max_range_m = c.F64();
  h.min_range_m = c.F64();
  h.height_offset_m = c.F64();
  h.nodes = c.U32();
  // Ranges are values: checked after the checksum. Dimensions shape the layout: checked now.
  *why = DescriptorIssue(h.rings, h.sectors, 1.0, 0.0, 0.0);
  if (!why->empty()) return std::nullopt;
  if (h.nodes > kSavedMapMaxNodes) {
    *why = "node count " + std::to_string(h.nodes) + " beyond the limit of " +
           std::to_string(kSavedMapMaxNodes);
    return std::nullopt;
  }
  const uint64_t min_bytes =
      uint64_t{h.nodes} * (kNodeFixedBytes + 4 * uint64_t{h.rings} * h.sectors) + kChecksumBytes;
  if (min_bytes > c.remaining()) {
    *why = "truncated or corrupt: node count " + std::to_string(h.nodes) + " needs at least " +
           std::to_string(min_bytes) + " bytes after the header, only " +
           std::to_string(c.remaining()) + " remain";
    return std::nullopt;
  }
  return h;
}

bool CheckLayout(std::string_view bytes, const Header& h, std::string* why) {
  const uint64_t descriptor_bytes = 4 * uint64_t{h.rings} * h.sectors;
  Cursor c(bytes, kHeaderBytes);
  for (size_t i = 0; i < h.nodes; ++i) {
    const size_t offset = c.offset();
    if (c.remaining() < kNodeFixedBytes + descriptor_bytes + kChecksumBytes) {
      *why = "truncated: " + Node(i, offset) + "only " + std::to_string(c.remaining()) +
             " bytes remain";
      return false;
    }
    c.Skip(kNodeFixedBytes - 8);
    const uint64_t planes = c.U32();
    const uint64_t edges = c.U32();
    if (planes + edges > kSavedMapMaxPointsPerNode) {
      *why = Node(i, offset) + std::to_string(planes) + " plane + " + std::to_string(edges) +
             " edge points, beyond the limit of " + std::to_string(kSavedMapMaxPointsPerNode);
      return false;
    }
    const uint64_t need = kPointBytes * (planes + edges) + descriptor_bytes;
    if (need + kChecksumBytes > c.remaining()) {
      *why = "truncated or corrupt: " + Node(i, offset) + std::to_string(planes) + " plane + " +
             std::to_string(edges) + " edge points and the descriptor need " +
             std::to_string(need) + " bytes, only " + std::to_string(c.remaining()) + " remain";
      return false;
    }
    c.Skip(static_cast<size_t>(need));
  }
  if (c.remaining() != kChecksumBytes) {
    *why = std::to_string(c.remaining() - kChecksumBytes) + " trailing bytes after the last node";
    return false;
  }
  return true;
}

bool GetPose(Cursor& c, Eigen::Isometry3d* T, std::string* why) {
  double v[7];
  for (double& x : v) x = c.F64();
  if (!std::all_of(v, v + 7, [](double x) { return std::isfinite(x); })) {
    *why = "not finite";
    return false;
  }
  Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  const double norm = q.norm();
  if (!(std::abs(norm - 1.0) <= kSavedMapQuaternionTolerance)) {
    *why = "quaternion norm " + std::to_string(norm) + " is not 1 (tolerance 1e-3)";
    return false;
  }
  q.coeffs() /= norm;
  T->setIdentity();
  T->linear() = q.toRotationMatrix();
  T->translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return true;
}

bool GetPoints(Cursor& c, uint32_t n, std::vector<Eigen::Vector3d>* points) {
  points->resize(n);
  for (auto& p : *points) {
    for (int k = 0; k < 3; ++k) p[k] = c.F32();
    if (!p.allFinite()) return false;
  }
  return true;
}

// One node from verified bytes; "" or what is wrong with it.
std::string GetNode(Cursor& c, size_t descriptor_size, SavedMapNode* node) {
  node->t_ns = c.I64();
  std::string why;
  if (!GetPose(c, &node->T_map_imu, &why)) return "T_map_imu " + why;
  if (!GetPose(c, &node->T_imu_lidar, &why)) return "T_imu_lidar " + why;
  const uint32_t planes = c.U32();
  const uint32_t edges = c.U32();
  if (!GetPoints(c, planes, &node->planes_lidar)) return "a plane point is not finite";
  if (!GetPoints(c, edges, &node->edges_lidar)) return "an edge point is not finite";
  node->descriptor.resize(descriptor_size);
  for (float& v : node->descriptor) {
    v = c.F32();
    if (!std::isfinite(v)) return "a descriptor value is not finite";
  }
  return {};
}

std::optional<SavedMap> Decode(std::string_view bytes, const Header& h, std::string* why) {
  *why = DescriptorIssue(h.rings, h.sectors, h.max_range_m, h.min_range_m, h.height_offset_m);
  if (!why->empty()) return std::nullopt;
  SavedMap map;
  map.file_version = h.version;
  map.descriptor_rings = static_cast<int>(h.rings);
  map.descriptor_sectors = static_cast<int>(h.sectors);
  map.descriptor_max_range_m = h.max_range_m;
  map.descriptor_min_range_m = h.min_range_m;
  map.descriptor_height_offset_m = h.height_offset_m;
  map.nodes.resize(h.nodes);  // ≤ (file size) / 128 nodes: checked by ParseHeader
  Cursor c(bytes, kHeaderBytes);
  for (size_t i = 0; i < map.nodes.size(); ++i) {
    const size_t offset = c.offset();
    const std::string issue = GetNode(c, size_t{h.rings} * h.sectors, &map.nodes[i]);
    if (!issue.empty()) {
      *why = Node(i, offset) + issue;
      return std::nullopt;
    }
    if (i > 0 && map.nodes[i].t_ns <= map.nodes[i - 1].t_ns) {
      *why = Node(i, offset) + "t_ns " + std::to_string(map.nodes[i].t_ns) +
             " not after the previous node's " + std::to_string(map.nodes[i - 1].t_ns);
      return std::nullopt;
    }
  }
  return map;
}

std::optional<SavedMap> ReadBytes(std::string_view bytes, std::string* why) {
  const std::optional<Header> header = ParseHeader(bytes, why);
  if (!header || !CheckLayout(bytes, *header, why)) return std::nullopt;
  const size_t body = bytes.size() - kChecksumBytes;
  const uint64_t stored = Cursor(bytes, body).U64();
  const uint64_t computed = Fnv1a64(bytes.substr(0, body));
  if (stored != computed) {
    *why = "checksum mismatch (stored " + Hex(stored) + ", computed " + Hex(computed) +
           "): the file is corrupt";
    return std::nullopt;
  }
  std::optional<SavedMap> map = Decode(bytes, *header, why);
  if (map && header->version == kSavedMapVersionManualFrame) ConvertManualFrameNodes(&*map);
  return map;
}

std::string ErrnoText() { return std::error_code(errno, std::generic_category()).message(); }

}  // namespace

bool WriteSavedMap(std::ostream& out, const SavedMap& map, std::string* error) {
  const std::string issue = MapIssue(map);
  if (!issue.empty()) {
    SetError(error, "map write: " + issue);
    return false;
  }
  Writer w(out);
  w.Bytes(kMagic);
  w.U32(kSavedMapVersion);
  w.U32(0);
  w.U32(static_cast<uint32_t>(map.descriptor_rings));
  w.U32(static_cast<uint32_t>(map.descriptor_sectors));
  w.F64(map.descriptor_max_range_m);
  w.F64(map.descriptor_min_range_m);
  w.F64(map.descriptor_height_offset_m);
  w.U32(static_cast<uint32_t>(map.nodes.size()));
  for (const SavedMapNode& node : map.nodes) {
    w.I64(node.t_ns);
    PutPose(w, node.T_map_imu);
    PutPose(w, node.T_imu_lidar);
    w.U32(static_cast<uint32_t>(node.planes_lidar.size()));
    w.U32(static_cast<uint32_t>(node.edges_lidar.size()));
    PutPoints(w, node.planes_lidar);
    PutPoints(w, node.edges_lidar);
    for (float v : node.descriptor) w.F32(v);
  }
  if (!w.Finish()) {
    SetError(error, "map write: stream write failed");
    return false;
  }
  return true;
}

std::optional<SavedMap> ReadSavedMap(std::istream& in, std::string* error) {
  std::string bytes;
  std::string why;
  std::optional<SavedMap> map;
  if (ReadAll(in, 0, &bytes, &why)) map = ReadBytes(bytes, &why);
  if (!map) SetError(error, "map file: " + why);
  return map;
}

bool SaveMapFile(const std::string& path, const SavedMap& map, std::string* error) {
  return ReplaceFile(
      path, "map write",
      [&map](std::ostream& out, std::string* why) { return WriteSavedMap(out, map, why); }, error);
}

std::optional<SavedMap> LoadMapFile(const std::string& path, std::string* error) {
  const std::string prefix = "map file " + path + ": ";
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) {
    SetError(error, prefix + "cannot open: " + (ec ? ec.message() : "no such file"));
    return std::nullopt;
  }
  if (!std::filesystem::is_regular_file(status)) {
    SetError(error, prefix + "not a regular file");
    return std::nullopt;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    SetError(error, prefix + "cannot open: " + ErrnoText());
    return std::nullopt;
  }
  std::string bytes;
  std::string why;
  std::optional<SavedMap> map;
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ReadAll(in, ec ? 0 : static_cast<size_t>(size), &bytes, &why)) map = ReadBytes(bytes, &why);
  if (!map) SetError(error, prefix + why);
  return map;
}

}  // namespace swlio::estimator
