// Saved map format (saved_map.h, estimator/map-format.md): round trip, the documented layout, and
// a clear refusal of every malformation; the merged PCD for viewers (map_pcd.h).
#include "swlio/estimator/map/saved_map.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

#include "swlio/estimator/map/map_pcd.h"

namespace swlio::estimator {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr size_t kHeaderBytes = 52;
constexpr size_t kNodeFixedBytes = 128;

// ---- The test's own view of the bytes (independent of the library's helpers).

uint64_t Fnv1a64(std::string_view bytes) {
  uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : bytes) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ULL;
  return h;
}

uint64_t GetLe(const std::string& bytes, size_t offset, int n) {
  uint64_t v = 0;
  for (int k = 0; k < n; ++k) {
    v |= uint64_t{static_cast<unsigned char>(bytes.at(offset + static_cast<size_t>(k)))} << (8 * k);
  }
  return v;
}

void PutLe(std::string* bytes, size_t offset, uint64_t v, int n) {
  for (int k = 0; k < n; ++k) {
    bytes->at(offset + static_cast<size_t>(k)) = static_cast<char>((v >> (8 * k)) & 0xff);
  }
}

void PutF64(std::string* bytes, size_t offset, double v) {
  PutLe(bytes, offset, std::bit_cast<uint64_t>(v), 8);
}

/// Recomputes the trailing checksum after an edit, so that the edit itself is what is tested.
void Reseal(std::string* bytes) {
  const size_t body = bytes->size() - 8;
  PutLe(bytes, body, Fnv1a64(std::string_view(*bytes).substr(0, body)), 8);
}

// ---- Maps.

Eigen::Isometry3d Pose(double yaw, double pitch, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  T.translation() = t;
  return T;
}

/// 3 nodes, each 2 plane + 1 edge points and a 2×3 descriptor: 188 bytes per node.
SavedMap SmallMap() {
  SavedMap map;
  map.descriptor_rings = 2;
  map.descriptor_sectors = 3;
  map.descriptor_max_range_m = 80.0;
  map.descriptor_min_range_m = 0.5;
  map.descriptor_height_offset_m = 2.0;
  for (int i = 0; i < 3; ++i) {
    SavedMapNode node;
    node.t_ns = 1'000'000'000LL * (i + 1);
    node.T_map_imu = Pose(0.3 * i, 0.05, Eigen::Vector3d(i, 2.0 * i, 0.1));
    node.T_imu_lidar = Pose(0.01, 0.0, Eigen::Vector3d(0.1, 0.0, 0.2));
    node.planes_lidar = {Eigen::Vector3d(1.0 + i, 2.0, 3.0), Eigen::Vector3d(-4.0, 5.5, 0.25)};
    node.edges_lidar = {Eigen::Vector3d(7.0, -8.0, 9.0 + i)};
    node.descriptor = {0.0f, 1.0f, 2.5f, 3.0f, 4.0f, static_cast<float>(i)};
    map.nodes.push_back(node);
  }
  return map;
}
constexpr size_t kSmallNodeBytes = kNodeFixedBytes + 12 * 3 + 4 * 6;

SavedMap RandomMap(int nodes, int planes, int edges, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SavedMap map;
  map.descriptor_rings = 20;
  map.descriptor_sectors = 60;
  map.descriptor_max_range_m = 80.0;
  map.descriptor_min_range_m = 1.0;
  map.descriptor_height_offset_m = 2.0;
  for (int i = 0; i < nodes; ++i) {
    SavedMapNode node;
    node.t_ns = 1'700'000'000'000'000'000LL + 100'000'000LL * i;
    node.T_map_imu = Pose(3.0 * u(rng), 0.2 * u(rng), 500.0 * Eigen::Vector3d(u(rng), u(rng), 0));
    node.T_imu_lidar = Pose(0.1 * u(rng), 0.1 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const auto point = [&]() -> Eigen::Vector3d {
      return 150.0 * Eigen::Vector3d(u(rng), u(rng), u(rng));
    };
    for (int k = 0; k < planes; ++k) node.planes_lidar.push_back(point());
    for (int k = 0; k < edges; ++k) node.edges_lidar.push_back(point());
    for (int k = 0; k < 20 * 60; ++k) node.descriptor.push_back(static_cast<float>(u(rng) + 1.0));
    map.nodes.push_back(node);
  }
  return map;
}

std::string Bytes(const SavedMap& map) {
  std::ostringstream out;
  std::string error;
  EXPECT_TRUE(WriteSavedMap(out, map, &error)) << error;
  return out.str();
}

std::optional<SavedMap> Read(const std::string& bytes, std::string* error) {
  std::istringstream in(bytes);
  return ReadSavedMap(in, error);
}

/// Reads bytes that must be refused; the error, which must say where it comes from.
std::string Refusal(const std::string& bytes) {
  std::string error;
  EXPECT_FALSE(Read(bytes, &error).has_value());
  EXPECT_THAT(error, StartsWith("map file: "));
  return error;
}

void ExpectSamePoints(const std::vector<Eigen::Vector3d>& read,
                      const std::vector<Eigen::Vector3d>& written) {
  ASSERT_EQ(read.size(), written.size());
  for (size_t k = 0; k < read.size(); ++k) {
    EXPECT_EQ(read[k], written[k].cast<float>().cast<double>()) << k;  // float precision
    EXPECT_LE((read[k] - written[k]).cwiseAbs().maxCoeff(), 8e-6) << k;
  }
}

void ExpectSameMap(const SavedMap& read, const SavedMap& written) {
  EXPECT_EQ(read.descriptor_rings, written.descriptor_rings);
  EXPECT_EQ(read.descriptor_sectors, written.descriptor_sectors);
  EXPECT_EQ(read.descriptor_max_range_m, written.descriptor_max_range_m);
  EXPECT_EQ(read.descriptor_min_range_m, written.descriptor_min_range_m);
  EXPECT_EQ(read.descriptor_height_offset_m, written.descriptor_height_offset_m);
  ASSERT_EQ(read.nodes.size(), written.nodes.size());
  for (size_t i = 0; i < read.nodes.size(); ++i) {
    const SavedMapNode& r = read.nodes[i];
    const SavedMapNode& w = written.nodes[i];
    EXPECT_EQ(r.t_ns, w.t_ns);
    EXPECT_LE((r.T_map_imu.matrix() - w.T_map_imu.matrix()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LE((r.T_imu_lidar.matrix() - w.T_imu_lidar.matrix()).cwiseAbs().maxCoeff(), 1e-12);
    ExpectSamePoints(r.planes_lidar, w.planes_lidar);
    ExpectSamePoints(r.edges_lidar, w.edges_lidar);
    EXPECT_EQ(r.descriptor, w.descriptor);
  }
}

// ---- Round trip and layout.

TEST(SavedMap, RoundTripKeepsPosesPointsAndDescriptors) {
  const SavedMap map = RandomMap(12, 40, 10, 7);
  std::string error;
  const auto read = Read(Bytes(map), &error);
  ASSERT_TRUE(read.has_value()) << error;
  ExpectSameMap(*read, map);
}

TEST(SavedMap, RoundTripWithoutDescriptorsOrNodes) {
  SavedMap empty;
  std::string error;
  auto read = Read(Bytes(empty), &error);
  ASSERT_TRUE(read.has_value()) << error;
  EXPECT_TRUE(read->nodes.empty());
  EXPECT_EQ(Bytes(empty).size(), kHeaderBytes + 8);

  SavedMap plain = SmallMap();
  plain.descriptor_rings = plain.descriptor_sectors = 0;
  for (auto& node : plain.nodes) node.descriptor.clear();
  plain.nodes[1].planes_lidar.clear();
  read = Read(Bytes(plain), &error);
  ASSERT_TRUE(read.has_value()) << error;
  ExpectSameMap(*read, plain);
}

TEST(SavedMap, LayoutFollowsTheDocumentedOffsets) {
  EXPECT_EQ(Fnv1a64("a"), 0xaf63dc4c8601ec8cULL);  // the published FNV-1a 64 test vector
  const SavedMap map = SmallMap();
  const std::string bytes = Bytes(map);
  ASSERT_EQ(bytes.size(), kHeaderBytes + 3 * kSmallNodeBytes + 8);
  EXPECT_EQ(bytes.substr(0, 8), "SWLIOMAP");
  EXPECT_EQ(GetLe(bytes, 8, 4), 2u);   // version
  EXPECT_EQ(GetLe(bytes, 12, 4), 0u);  // flags
  EXPECT_EQ(GetLe(bytes, 16, 4), 2u);  // rings
  EXPECT_EQ(GetLe(bytes, 20, 4), 3u);  // sectors
  EXPECT_EQ(std::bit_cast<double>(GetLe(bytes, 24, 8)), 80.0);
  EXPECT_EQ(std::bit_cast<double>(GetLe(bytes, 32, 8)), 0.5);
  EXPECT_EQ(std::bit_cast<double>(GetLe(bytes, 40, 8)), 2.0);
  EXPECT_EQ(GetLe(bytes, 48, 4), 3u);  // nodes
  const size_t node1 = kHeaderBytes + kSmallNodeBytes;
  EXPECT_EQ(GetLe(bytes, node1, 8), 2'000'000'000u);
  EXPECT_EQ(std::bit_cast<double>(GetLe(bytes, node1 + 8, 8)), 1.0);   // T_map_imu tx
  EXPECT_EQ(std::bit_cast<double>(GetLe(bytes, node1 + 16, 8)), 2.0);  // ty
  const Eigen::Quaterniond q(map.nodes[1].T_map_imu.linear());
  EXPECT_NEAR(std::abs(std::bit_cast<double>(GetLe(bytes, node1 + 56, 8))), std::abs(q.w()),
              1e-15);                                                  // qw last
  EXPECT_EQ(std::bit_cast<double>(GetLe(bytes, node1 + 64, 8)), 0.1);  // T_imu_lidar tx
  EXPECT_EQ(GetLe(bytes, node1 + 120, 4), 2u);                         // planes
  EXPECT_EQ(GetLe(bytes, node1 + 124, 4), 1u);                         // edges
  EXPECT_EQ(std::bit_cast<float>(static_cast<uint32_t>(GetLe(bytes, node1 + 128, 4))), 2.0f);
  EXPECT_EQ(std::bit_cast<float>(static_cast<uint32_t>(GetLe(bytes, node1 + 128 + 24, 4))),
            7.0f);  // first edge x
  EXPECT_EQ(std::bit_cast<float>(static_cast<uint32_t>(GetLe(bytes, node1 + 128 + 36 + 8, 4))),
            2.5f);  // descriptor[2]
  const size_t body = bytes.size() - 8;
  EXPECT_EQ(GetLe(bytes, body, 8), Fnv1a64(std::string_view(bytes).substr(0, body)));
}

// ---- Malformations.

TEST(SavedMap, TruncationAtEveryOffsetFailsCleanly) {
  const std::string bytes = Bytes(SmallMap());
  for (size_t n = 0; n < bytes.size(); ++n) {
    EXPECT_THAT(Refusal(bytes.substr(0, n)), HasSubstr("truncated")) << "at " << n;
  }
}

TEST(SavedMap, AnyFlippedByteIsRejected) {
  const std::string bytes = Bytes(SmallMap());
  for (size_t i = 0; i < bytes.size(); ++i) {
    std::string flipped = bytes;
    flipped[i] = static_cast<char>(flipped[i] ^ 0x10);
    Refusal(flipped);
  }
  std::string flipped = bytes;
  const size_t in_point = kHeaderBytes + kNodeFixedBytes + 5;  // node 0's first plane point
  flipped[in_point] = static_cast<char>(flipped[in_point] ^ 0x01);
  EXPECT_THAT(Refusal(flipped), HasSubstr("checksum mismatch"));
  flipped = bytes;
  flipped.back() = static_cast<char>(flipped.back() ^ 0x01);  // the checksum itself
  EXPECT_THAT(Refusal(flipped), HasSubstr("checksum mismatch"));
}

TEST(SavedMap, WrongMagicIsRejected) {
  std::string bytes = Bytes(SmallMap());
  bytes[7] = 'Q';
  EXPECT_THAT(Refusal(bytes), HasSubstr("bad magic"));
  EXPECT_THAT(Refusal("# .PCD v0.7 - Point Cloud Data file format\n"), HasSubstr("bad magic"));
  EXPECT_THAT(Refusal("SWL"), HasSubstr("truncated header"));
}

TEST(SavedMap, OtherVersionsAndFlagsAreRejected) {
  std::string bytes = Bytes(SmallMap());
  for (const uint32_t version : {0u, 3u}) {
    PutLe(&bytes, 8, version, 4);
    Reseal(&bytes);
    const std::string unsupported = "unsupported version " + std::to_string(version);
    EXPECT_THAT(Refusal(bytes), HasSubstr(unsupported));
    EXPECT_THAT(Refusal(bytes.substr(0, 12)), HasSubstr(unsupported));
  }
  bytes = Bytes(SmallMap());
  PutLe(&bytes, 12, 1, 4);
  Reseal(&bytes);
  EXPECT_THAT(Refusal(bytes), HasSubstr("unsupported header flags"));
}

// A map saved before issue 32 (version 1: features and extrinsic in the RoboSense manual's
// frame, y forward, x right) is converted on reading: features turned into the drivers' frame
// (x forward, y left), the extrinsic by Rz(+90°), so every feature stays where it was in the
// map frame; read as version 2 it would not (the test can tell the two apart).
TEST(SavedMap, Version1IsConvertedToTheDriversFrame) {
  const SavedMap old = SmallMap();
  std::string bytes = Bytes(old);
  PutLe(&bytes, 8, 1, 4);
  Reseal(&bytes);
  std::string error;
  const auto read = Read(bytes, &error);
  ASSERT_TRUE(read.has_value()) << error;
  EXPECT_EQ(read->file_version, 1u);
  EXPECT_EQ(Read(Bytes(old), &error)->file_version, 2u);
  ASSERT_EQ(read->nodes.size(), old.nodes.size());
  for (size_t i = 0; i < old.nodes.size(); ++i) {
    const SavedMapNode& a = old.nodes[i];
    const SavedMapNode& b = read->nodes[i];
    // The first plane point (1 + i, 2, 3) in the manual frame is (2, −1 − i, 3) now.
    EXPECT_EQ(b.planes_lidar[0], Eigen::Vector3d(2.0, -1.0 - static_cast<double>(i), 3.0));
    const Eigen::Isometry3d T_map_old = a.T_map_imu * a.T_imu_lidar;
    const Eigen::Isometry3d T_map_new = b.T_map_imu * b.T_imu_lidar;
    for (size_t k = 0; k < a.planes_lidar.size(); ++k) {
      EXPECT_LT((T_map_new * b.planes_lidar[k] - T_map_old * a.planes_lidar[k]).norm(), 1e-12);
      EXPECT_GT((T_map_old * b.planes_lidar[k] - T_map_old * a.planes_lidar[k]).norm(), 1.0);
    }
    EXPECT_LT((T_map_new * b.edges_lidar[0] - T_map_old * a.edges_lidar[0]).norm(), 1e-12);
    EXPECT_EQ(b.descriptor, a.descriptor);  // gravity-frame descriptors: unchanged
  }
  // Written again, it is version 2 and reads back as it is.
  const auto again = Read(Bytes(*read), &error);
  ASSERT_TRUE(again.has_value()) << error;
  EXPECT_EQ(again->file_version, 2u);
  ExpectSameMap(*again, *read);
}

TEST(SavedMap, HugeCountsAreRefusedBeforeAllocating) {
  const std::string good = Bytes(SmallMap());
  std::string bytes = good;
  PutLe(&bytes, 48, 0xffffffffu, 4);
  EXPECT_THAT(Refusal(bytes), HasSubstr("node count 4294967295 beyond the limit"));
  bytes = good;
  PutLe(&bytes, 48, 9'999'999, 4);
  EXPECT_THAT(Refusal(bytes), HasSubstr("node count 9999999 needs at least"));
  bytes = good;
  PutLe(&bytes, kHeaderBytes + 120, 0xffffffffu, 4);  // node 0's plane count
  EXPECT_THAT(Refusal(bytes), HasSubstr("beyond the limit of 1000000"));
  bytes = good;
  PutLe(&bytes, kHeaderBytes + 120, 600'000, 4);  // each count within the limit, not the sum
  PutLe(&bytes, kHeaderBytes + 124, 600'000, 4);
  EXPECT_THAT(Refusal(bytes), HasSubstr("600000 plane + 600000 edge points, beyond the limit"));
  bytes = good;
  PutLe(&bytes, kHeaderBytes + kSmallNodeBytes + 124, 999'000, 4);  // node 1's edge count
  EXPECT_THAT(Refusal(bytes), HasSubstr("node 1 (at byte 240): 2 plane + 999000 edge points"));
  bytes = good;
  PutLe(&bytes, 16, 100'000, 4);  // rings
  EXPECT_THAT(Refusal(bytes), HasSubstr("beyond the limit of 1024"));
  bytes = good;
  PutLe(&bytes, 20, 0, 4);  // sectors 0, rings 2
  EXPECT_THAT(Refusal(bytes), HasSubstr("both be 0 or both be positive"));
}

TEST(SavedMap, TrailingBytesAreRejected) {
  EXPECT_THAT(Refusal(Bytes(SmallMap()) + "abc"), HasSubstr("3 trailing bytes"));
  std::string bytes = Bytes(SmallMap());
  bytes.insert(bytes.size() - 8, 12, '\0');  // room for a point nobody counted
  Reseal(&bytes);
  EXPECT_THAT(Refusal(bytes), HasSubstr("12 trailing bytes"));
}

TEST(SavedMap, NonFiniteValuesAreRejected) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const size_t node1 = kHeaderBytes + kSmallNodeBytes;
  std::string bytes = Bytes(SmallMap());
  PutF64(&bytes, node1 + 8, nan);
  Reseal(&bytes);
  EXPECT_THAT(Refusal(bytes), HasSubstr("node 1 (at byte 240): T_map_imu not finite"));
  bytes = Bytes(SmallMap());
  PutF64(&bytes, node1 + 64 + 48, std::numeric_limits<double>::infinity());  // T_imu_lidar qw
  Reseal(&bytes);
  EXPECT_THAT(Refusal(bytes), HasSubstr("T_imu_lidar not finite"));
  bytes = Bytes(SmallMap());
  PutLe(&bytes, node1 + 128 + 16, std::bit_cast<uint32_t>(std::nanf("")), 4);
  Reseal(&bytes);
  EXPECT_THAT(Refusal(bytes), HasSubstr("plane point is not finite"));
  bytes = Bytes(SmallMap());
  PutLe(&bytes, node1 + 128 + 36, std::bit_cast<uint32_t>(-INFINITY), 4);
  Reseal(&bytes);
  EXPECT_THAT(Refusal(bytes), HasSubstr("descriptor value is not finite"));
  bytes = Bytes(SmallMap());
  PutF64(&bytes, 24, nan);
  Reseal(&bytes);
  EXPECT_THAT(Refusal(bytes), HasSubstr("descriptor ranges or height offset not finite"));
}

TEST(SavedMap, QuaternionsMustBeUnit) {
  const SavedMap map = SmallMap();
  const size_t q0 = kHeaderBytes + 8 + 24;  // node 0's T_map_imu qx
  const std::string good = Bytes(map);
  auto scaled = [&](double s) {
    std::string bytes = good;
    for (size_t k = 0; k < 4; ++k) {
      PutF64(&bytes, q0 + 8 * k, s * std::bit_cast<double>(GetLe(good, q0 + 8 * k, 8)));
    }
    Reseal(&bytes);
    return bytes;
  };
  EXPECT_THAT(Refusal(scaled(1.01)), HasSubstr("node 0 (at byte 52): T_map_imu quaternion norm"));
  EXPECT_THAT(Refusal(scaled(0.0)), HasSubstr("quaternion norm"));
  std::string error;
  const auto read = Read(scaled(1.0009), &error);  // within tolerance: renormalized
  ASSERT_TRUE(read.has_value()) << error;
  const Eigen::Matrix3d R = read->nodes[0].T_map_imu.linear();
  EXPECT_LE((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-14);
  EXPECT_LE((R - map.nodes[0].T_map_imu.linear()).norm(), 1e-12);
}

TEST(SavedMap, NodesMustBeInIncreasingTime) {
  std::string bytes = Bytes(SmallMap());
  PutLe(&bytes, kHeaderBytes + 2 * kSmallNodeBytes, 2'000'000'000, 8);  // node 2 = node 1
  Reseal(&bytes);
  EXPECT_THAT(Refusal(bytes), HasSubstr("node 2 (at byte 428): t_ns 2000000000 not after"));
}

TEST(SavedMap, FailingStreamsAreReported) {
  EXPECT_THAT(Refusal(""), HasSubstr("truncated header: 0 of 52 bytes"));
  std::ostringstream out;
  out.setstate(std::ios::badbit);
  std::string error;
  EXPECT_FALSE(WriteSavedMap(out, SmallMap(), &error));
  EXPECT_THAT(error, HasSubstr("map write: stream write failed"));
}

// ---- Writing refuses what reading would refuse, and writes nothing then.

TEST(SavedMap, WriteRefusesInvalidContent) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto refused = [](const SavedMap& map, const std::string& what) {
    std::ostringstream out;
    std::string error;
    EXPECT_FALSE(WriteSavedMap(out, map, &error)) << what;
    EXPECT_THAT(error, StartsWith("map write: ")) << what;
    EXPECT_THAT(error, HasSubstr(what));
    EXPECT_TRUE(out.str().empty()) << what;
  };
  SavedMap map = SmallMap();
  map.nodes[1].T_map_imu.translation().x() = nan;
  refused(map, "node 1: T_map_imu is not a finite rigid transform");
  map = SmallMap();
  map.nodes[2].T_imu_lidar.linear() *= 2.0;
  refused(map, "node 2: T_imu_lidar is not a finite rigid transform");
  map = SmallMap();
  map.nodes[0].planes_lidar[1].z() = nan;
  refused(map, "node 0: a point is not finite or beyond float range");
  map = SmallMap();
  map.nodes[0].edges_lidar[0].x() = 1e39;
  refused(map, "node 0: a point is not finite or beyond float range");
  map = SmallMap();
  map.nodes[1].descriptor.pop_back();
  refused(map, "node 1: descriptor has 5 values, the map's dimensions need 6");
  map = SmallMap();
  map.nodes[1].descriptor[0] = std::nanf("");
  refused(map, "node 1: descriptor value not finite");
  map = SmallMap();
  map.nodes[2].t_ns = map.nodes[1].t_ns;
  refused(map, "node 2: t_ns not after the previous node's");
  map = SmallMap();
  map.descriptor_sectors = 0;
  refused(map, "both be 0 or both be positive");
  map = SmallMap();
  map.descriptor_min_range_m = 100.0;
  refused(map, "descriptor ranges need 0 <= min < max");
  map = SmallMap();
  map.descriptor_rings = -1;
  refused(map, "negative descriptor size");
}

// ---- Files.

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("swlio_saved_map_" + std::to_string(::getpid()) + "_" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::vector<std::string> Names() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

TEST(SavedMap, SaveAndLoadFileLeavesNoTemporary) {
  TempDir dir;
  const std::string path = (dir.path() / "site.swlmap").string();
  std::string error;
  SavedMap map = RandomMap(5, 30, 5, 3);
  ASSERT_TRUE(SaveMapFile(path, map, &error)) << error;
  EXPECT_EQ(dir.Names(), std::vector<std::string>{"site.swlmap"});
  auto loaded = LoadMapFile(path, &error);
  ASSERT_TRUE(loaded.has_value()) << error;
  ExpectSameMap(*loaded, map);

  // Replacing works; a refused map leaves the old file and no temporary.
  map.nodes.pop_back();
  ASSERT_TRUE(SaveMapFile(path, map, &error)) << error;
  map.nodes[0].T_map_imu.translation().y() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(SaveMapFile(path, map, &error));
  EXPECT_THAT(error, HasSubstr("map write: node 0: T_map_imu"));
  EXPECT_EQ(dir.Names(), std::vector<std::string>{"site.swlmap"});
  loaded = LoadMapFile(path, &error);
  ASSERT_TRUE(loaded.has_value()) << error;
  EXPECT_EQ(loaded->nodes.size(), 4u);
}

TEST(SavedMap, LoadFileErrorsNameThePath) {
  TempDir dir;
  const std::string missing = (dir.path() / "missing.swlmap").string();
  std::string error;
  EXPECT_FALSE(LoadMapFile(missing, &error).has_value());
  EXPECT_THAT(error, StartsWith("map file " + missing + ": cannot open"));
  EXPECT_FALSE(LoadMapFile(dir.path().string(), &error).has_value());
  EXPECT_THAT(error, HasSubstr("not a regular file"));
  const std::string corrupt = (dir.path() / "corrupt.swlmap").string();
  std::ofstream(corrupt, std::ios::binary) << Bytes(SmallMap()).substr(0, 100);
  EXPECT_FALSE(LoadMapFile(corrupt, &error).has_value());
  EXPECT_THAT(error, StartsWith("map file " + corrupt + ": truncated"));
  EXPECT_FALSE(SaveMapFile((dir.path() / "no" / "such.swlmap").string(), SmallMap(), &error));
  EXPECT_THAT(error, HasSubstr("cannot create"));
}

// ---- Merged PCD.

struct Pcd {
  std::vector<std::string> header;
  std::vector<Eigen::Vector3f> points;
  size_t body_bytes = 0;
};

Pcd ParsePcd(const std::string& text) {
  Pcd pcd;
  const std::string data = "DATA binary\n";
  const size_t end = text.find(data);
  EXPECT_NE(end, std::string::npos);
  if (end == std::string::npos) return pcd;
  std::istringstream lines(text.substr(0, end + data.size()));
  for (std::string line; std::getline(lines, line);) pcd.header.push_back(line);
  const std::string body = text.substr(end + data.size());
  pcd.body_bytes = body.size();
  for (size_t off = 0; off + 12 <= body.size(); off += 12) {
    Eigen::Vector3f p;
    for (int a = 0; a < 3; ++a) {
      p[a] = std::bit_cast<float>(static_cast<uint32_t>(GetLe(body, off + 4 * size_t(a), 4)));
    }
    pcd.points.push_back(p);
  }
  return pcd;
}

Pcd Merged(const SavedMap& map, double voxel_m, long* n) {
  std::ostringstream out;
  std::string error;
  *n = WriteMergedPcd(out, map, voxel_m, &error);
  EXPECT_GE(*n, 0) << error;
  return ParsePcd(out.str());
}

SavedMapNode NodeAt(int64_t t_ns,
                    const Eigen::Isometry3d& T_map_imu,
                    std::vector<Eigen::Vector3d> planes,
                    std::vector<Eigen::Vector3d> edges) {
  SavedMapNode node;
  node.t_ns = t_ns;
  node.T_map_imu = T_map_imu;
  node.planes_lidar = std::move(planes);
  node.edges_lidar = std::move(edges);
  return node;
}

TEST(MapPcd, HeaderHasEveryField) {
  SavedMap map;
  map.nodes.push_back(NodeAt(1, Eigen::Isometry3d::Identity(),
                             {Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(2.5, 0.5, 0.5)}, {}));
  long n = 0;
  const Pcd pcd = Merged(map, 1.0, &n);
  EXPECT_EQ(n, 2);
  EXPECT_EQ(pcd.header, (std::vector<std::string>{
                            "# .PCD v0.7 - Point Cloud Data file format", "VERSION 0.7",
                            "FIELDS x y z", "SIZE 4 4 4", "TYPE F F F", "COUNT 1 1 1", "WIDTH 2",
                            "HEIGHT 1", "VIEWPOINT 0 0 0 1 0 0 0", "POINTS 2", "DATA binary"}));
  EXPECT_EQ(pcd.body_bytes, 24u);
}

TEST(MapPcd, OnePointPerVoxel) {
  SavedMap map;
  // Node 0: planes in voxels (0,0,0) ×2, (1,0,0), (-1,0,0); an edge in (0,0,0) again.
  map.nodes.push_back(NodeAt(1, Eigen::Isometry3d::Identity(),
                             {Eigen::Vector3d(0.1, 0.1, 0.1), Eigen::Vector3d(0.2, 0.2, 0.2),
                              Eigen::Vector3d(1.5, 0.1, 0.1), Eigen::Vector3d(-0.1, 0.5, 0.5)},
                             {Eigen::Vector3d(0.3, 0.3, 0.3)}));
  // Node 1: one point in voxel (0,0,0) seen from elsewhere, one in a new voxel (5,5,5).
  map.nodes.push_back(NodeAt(2, Pose(0, 0, Eigen::Vector3d(5, 5, 5)),
                             {Eigen::Vector3d(-4.8, -4.8, -4.8), Eigen::Vector3d(0.5, 0.5, 0.5)},
                             {}));
  long n = 0;
  const Pcd pcd = Merged(map, 1.0, &n);
  EXPECT_EQ(n, 4);
  ASSERT_EQ(pcd.points.size(), 4u);
  EXPECT_THAT(pcd.header, ::testing::Contains("POINTS 4"));
  // Voxel order: (-1,0,0), (0,0,0) [centroid of 0.1, 0.2, 0.3, 0.2], (1,0,0), (5,5,5).
  EXPECT_TRUE(pcd.points[0].isApprox(Eigen::Vector3f(-0.1f, 0.5f, 0.5f)));
  EXPECT_TRUE(pcd.points[1].isApprox(Eigen::Vector3f(0.2f, 0.2f, 0.2f), 1e-5f));
  EXPECT_TRUE(pcd.points[2].isApprox(Eigen::Vector3f(1.5f, 0.1f, 0.1f)));
  EXPECT_TRUE(pcd.points[3].isApprox(Eigen::Vector3f(5.5f, 5.5f, 5.5f)));
  // A finer grid separates everything.
  EXPECT_EQ(Merged(map, 0.07, &n).points.size(), 6u);  // only the two 0.2s share
}

TEST(MapPcd, PointsAreInTheMapFrame) {
  SavedMap map;
  map.nodes.push_back(NodeAt(1, Eigen::Isometry3d::Identity(), {Eigen::Vector3d(1, 0, 0)}, {}));
  long n = 0;
  const Eigen::Vector3f at_origin = Merged(map, 0.01, &n).points.at(0);
  map.nodes[0].T_map_imu.translation() = Eigen::Vector3d(10, 20, 30);
  EXPECT_TRUE(Merged(map, 0.01, &n).points.at(0).isApprox(at_origin + Eigen::Vector3f(10, 20, 30)));
  // Full chain p_map = T_map_imu · T_imu_lidar · p_lidar: lidar (1,0,0) → imu (2,0,0) → a
  // quarter turn about z → (0,2,0) → + (10,20,30).
  map.nodes[0].T_map_imu = Pose(std::numbers::pi / 2, 0, Eigen::Vector3d(10, 20, 30));
  map.nodes[0].T_imu_lidar = Pose(0, 0, Eigen::Vector3d(1, 0, 0));
  EXPECT_TRUE(Merged(map, 0.01, &n).points.at(0).isApprox(Eigen::Vector3f(10, 22, 30)));
}

TEST(MapPcd, RejectsBadVoxelsAndPoints) {
  SavedMap map = SmallMap();
  std::string error;
  for (double voxel : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    std::ostringstream out;
    EXPECT_EQ(WriteMergedPcd(out, map, voxel, &error), -1) << voxel;
    EXPECT_THAT(error, HasSubstr("merged cloud: voxel size"));
    EXPECT_TRUE(out.str().empty());
  }
  map.nodes[1].T_map_imu.translation().z() = 1e12;
  std::ostringstream out;
  EXPECT_EQ(WriteMergedPcd(out, map, 0.1, &error), -1);
  EXPECT_THAT(error, HasSubstr("merged cloud: node 1: a point in the map frame"));
}

TEST(MapPcd, SaveMergedPcdWritesTheFile) {
  TempDir dir;
  const std::string path = (dir.path() / "site.pcd").string();
  std::string error;
  ASSERT_TRUE(SaveMergedPcd(path, SmallMap(), 0.1, &error)) << error;
  EXPECT_EQ(dir.Names(), std::vector<std::string>{"site.pcd"});
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Pcd pcd = ParsePcd(text);
  EXPECT_EQ(pcd.points.size(), 9u);  // 3 nodes × 3 separate points
  EXPECT_EQ(pcd.body_bytes, 9u * 12);
  EXPECT_FALSE(SaveMergedPcd(path, SmallMap(), 0.0, &error));
  EXPECT_EQ(dir.Names(), std::vector<std::string>{"site.pcd"});
}

}  // namespace
}  // namespace swlio::estimator
