#pragma once
/// @file
/// Scan Context place descriptor (Kim & Kim, "Scan Context: Egocentric Spatial Descriptor for
/// Place Recognition within 3D Point Cloud Map", IROS 2018), for loop-candidate search and
/// global relocalization in a saved map.
///
/// The horizontal plane around the sensor is cut into `rings` annuli of equal width
/// (max_range_m / rings) and `sectors` azimuth wedges of equal angle (2π / sectors); each bin
/// keeps the largest height of its points (paper §III-A, eq. (2) with the max-height encoding).
/// A change of the sensor's yaw is a circular shift of the columns, which the comparison
/// searches (§III-B, eqs. (5)–(6)); the ring key (share of occupied sectors per ring) does not
/// depend on yaw and ranks candidates before the full comparison (§III-C).
///
/// Frames: "gravity" is a frame centred at the sensor with z up (along −gravity) and x the
/// keyframe's heading projected on the horizontal plane (see GravityAlignedFromBody).
///
/// Yaw convention (verified by scan_context_test.cpp, ScanContextCompare.*):
///   azimuth(p) = atan2(p.y, p.x) ∈ [−π, π]; sector k covers azimuths
///   [−π + k·2π/sectors, −π + (k+1)·2π/sectors), counter-clockwise seen from above.
///   A match with column shift s compares query column j with candidate column
///   (j + s) mod sectors, and yaw_rad = s·2π/sectors wrapped to (−π, π]. Then
///   R_candidate_query = Rz(yaw_rad): a point p_query in the query's gravity frame is, up to
///   the (unknown) translation between the two places, Rz(yaw_rad)·p_query in the candidate's
///   gravity frame. Example: the sensor turned by +θ (points seen as Rz(−θ)·p) gives
///   yaw_rad ≈ θ against the unturned descriptor, within one sector.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <utility>
#include <vector>

#include "swlio/core/config_issue.h"

namespace swlio::estimator {

struct ScanContextConfig {
  int rings = 20;             ///< radial bins, each max_range_m / rings wide
  int sectors = 60;           ///< azimuth bins (6° each by default)
  double max_range_m = 60.0;  ///< points at horizontal range ≥ this are ignored
  double min_range_m = 1.0;   ///< points closer (the robot itself) are ignored
  /// Added to z (gravity frame, origin at the sensor) so that bin values are > 0 above the
  /// ground; values clamp at 0 (a bin whose points are all that low reads as empty).
  double height_offset_m = 2.0;
  int candidates = 10;        ///< ring-key nearest neighbours compared in full per query
  double max_distance = 0.3;  ///< a match needs a descriptor distance below this, in (0, 1]

  ConfigIssues Validate() const;
};

/// rings × sectors matrix (row = ring, col = sector), value = max height (z + height_offset_m,
/// ≥ 0) of the points in the bin, 0 where empty.
struct ScanContext {
  int rings = 0;
  int sectors = 0;
  std::vector<float> cells;     ///< row-major, rings·sectors, metres (≥ 0)
  std::vector<float> ring_key;  ///< per ring: share of sectors with a value > 0, in [0, 1]

  /// @note ring ∈ [0, rings), sector ∈ [0, sectors); not range-checked.
  float at(int ring, int sector) const {
    return cells[static_cast<size_t>(ring) * static_cast<size_t>(sectors) +
                 static_cast<size_t>(sector)];
  }
};

/// Builds the descriptor from points already expressed in the gravity frame (centred at the
/// sensor, x forward at the keyframe's yaw, z up). Non-finite points are skipped. Sector 0
/// starts at azimuth −π (atan2(y, x)), going counter-clockwise.
ScanContext MakeScanContext(const ScanContextConfig& config,
                            const std::vector<Eigen::Vector3d>& points_gravity);

/// Convenience: points in a LiDAR frame, with T_gravity_lidar (the rotation removing roll and
/// pitch, plus the LiDAR's offset from the chosen origin).
ScanContext MakeScanContext(const ScanContextConfig& config,
                            const Eigen::Isometry3d& T_gravity_lidar,
                            const std::vector<Eigen::Vector3d>& points_lidar);

/// A descriptor from stored cells (e.g. read back from a saved map), with its ring key
/// recomputed. `cells` must hold rings·sectors values, row-major.
ScanContext ScanContextFromCells(int rings, int sectors, std::vector<float> cells);

/// The rotation that removes roll and pitch of R_world_body but keeps nothing of its yaw:
/// returns R such that R·v (v in body) is v in a frame with z = world z and x = the body's x
/// axis projected on the horizontal plane. Use it as the rotation of T_gravity_lidar (times
/// R_body_lidar).
/// @note Undefined heading when the body's x axis is vertical; then x = world x is used.
Eigen::Matrix3d GravityAlignedFromBody(const Eigen::Matrix3d& R_world_body);

struct ScanContextMatch {
  /// Mean over column pairs where both columns are non-empty of (1 − cosine similarity), in
  /// [0, 1]; 1.0 when no column pair is comparable (or the descriptors' sizes differ).
  double distance = 1.0;
  /// Best column shift s ∈ [0, sectors): query column j ↔ candidate column (j + s) mod sectors.
  int shift = 0;
  /// Yaw of R_candidate_query, s·2π/sectors in (−π, π]: rotating query points by Rz(yaw_rad)
  /// aligns them with the candidate (see the convention in the file comment).
  double yaw_rad = 0.0;
};

/// Best column shift between two descriptors (all shifts tried; ties keep the smallest shift).
/// Float maths, column norms computed once: O(rings·sectors²).
ScanContextMatch CompareScanContexts(const ScanContext& query, const ScanContext& candidate);

/// A searchable set of descriptors: brute-force ring-key nearest neighbours (Euclidean), then a
/// full comparison of the `config.candidates` best by ring key. Indices are insertion order.
class ScanContextDatabase {
 public:
  explicit ScanContextDatabase(const ScanContextConfig& config);

  /// Stores the descriptor and returns its index.
  size_t Add(ScanContext descriptor);
  size_t size() const { return descriptors_.size(); }
  const ScanContext& at(size_t i) const { return descriptors_[i]; }
  /// Frees descriptor i's memory; it stays in the index order and never matches again.
  void Release(size_t i) { descriptors_[i] = ScanContext{}; }

  /// Up to `max_results` matches with distance < config.max_distance, best first (ties by
  /// index), considering only indices for which `allowed(i)` is true (e.g. old enough); an
  /// empty `allowed` allows all. Descriptors whose size differs from the query's never match.
  std::vector<std::pair<size_t, ScanContextMatch>> Query(
      const ScanContext& query,
      size_t max_results,
      const std::function<bool(size_t)>& allowed) const;

 private:
  ScanContextConfig config_;
  std::vector<ScanContext> descriptors_;
};

}  // namespace swlio::estimator
