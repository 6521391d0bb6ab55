#pragma once
/// @file
/// Absolute and relative pose errors and their statistics, with evo's (v1.36) conventions.
///
/// - APE: translation error ‖p_est,i − p_ref,i‖; other relations use E_i = T_est,i⁻¹ T_ref,i.
/// - RPE for a pair (i, j): E = (Q_i⁻¹ Q_j)⁻¹ (P_i⁻¹ P_j), Q the reference, P the estimate;
///   "inverse" transposes the rotation block (evo's se3_inverse).
/// - Relations: translation ‖E_t‖; angle = rotation angle of E_R (its quaternion's, as scipy's
///   Rotation.from_matrix(...).magnitude()); full = ‖E − I‖_F; rotation part = ‖E_R − I‖_F.
/// - Pairs (consecutive, not "all pairs"), chosen on the estimate:
///   frames: ids 0, δ, 2δ, … < n, pairs between successive ids;
///   metres: walk the path, add ‖p_k − p_{k−1}‖ and record k each time the sum reaches δ (then
///   reset the sum); index 0 is not recorded; pairs between successive recorded ids.
/// - Statistics: max, mean, median (mean of the middle two for even n), min, rmse, sse, std
///   (population, ddof 0).

#include "swlio/eval/trajectory.h"

#include <Eigen/Core>

#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace swlio::eval {

enum class PoseRelation { kTranslation, kAngleDeg, kAngleRad, kFull, kRotationPart };
enum class DeltaUnit { kFrames, kMeters };

/// Parses evo-style names: "trans" / "trans_part", "angle_deg", "angle_rad", "full", "rot_part".
PoseRelation ParsePoseRelation(const std::string& text);
DeltaUnit ParseDeltaUnit(const std::string& text);  ///< "frames" or "m"
/// Human-readable name with unit, e.g. "translation part (m)".
std::string Describe(PoseRelation relation);

struct Statistics {
  std::size_t n = 0;
  double max = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double min = 0.0;
  double rmse = 0.0;
  double sse = 0.0;
  double std = 0.0;
};

/// Statistics of `errors`; throws EvalError when empty.
Statistics ComputeStatistics(std::span<const double> errors);

/// Rotation angle (rad, in [0, π]) of a (nearly) orthonormal matrix via its normalised quaternion.
double RotationAngleRad(const Eigen::Matrix3d& R);

/// The scalar error of error pose E for `relation`.
double RelationError(const Pose& E, PoseRelation relation);

/// APE per pose of two paired trajectories (same size).
std::vector<double> ApeErrors(const Trajectory& ref, const Trajectory& est, PoseRelation relation);

using IdPairs = std::vector<std::pair<std::size_t, std::size_t>>;

/// Consecutive pairs of `poses` for a delta in frames (integer ≥ 1) or metres (> 0); throws
/// EvalError for a bad delta or when no pair results.
IdPairs RpePairs(const Trajectory& trajectory, double delta, DeltaUnit unit);

/// The RPE error pose for a pair.
Pose RpeErrorPose(const Pose& Q_i, const Pose& Q_j, const Pose& P_i, const Pose& P_j);

struct RpeResult {
  IdPairs pairs;  ///< (i, j) per error
  std::vector<double> errors;
};

/// RPE of paired trajectories; pairs are chosen on the estimate, as evo does by default.
RpeResult Rpe(const Trajectory& ref,
              const Trajectory& est,
              double delta,
              DeltaUnit unit,
              PoseRelation relation);

}  // namespace swlio::eval
