#pragma once
/// @file
/// Rate-limited map correction for the output (issue 8: "the planner must not see teleports").
/// Loop closure moves the correction T_map_odom in steps; the published pose is
/// T_map_odom · T_odom_imu, so a step would move the robot's output pose at once. This class
/// follows the target correction at a bounded rate instead, measured where it matters, at the
/// robot: between the output pose with the current correction, A = C · T, and with the target,
/// B = C* · T, the difference D = A⁻¹ B = Exp([δp; δφ]) (robot frame) is walked along by at
/// most `max_rate_mps` · Δt in position and `max_rate_radps` · Δt in rotation per step
/// (Δt: output time since the last step), so C ← A · Exp(f · Log D) · T⁻¹ with
/// f = min(1, v Δt / |δp|, ω Δt / |δφ|). A rotation of C about the map origin would swing a
/// robot far from it by metres; done this way the output moves by no more than the limits.
/// Pure: output time passed in.

#include <Eigen/Geometry>
#include <cstdint>

namespace swlio::estimator {

struct CorrectionSlewConfig {
  double max_rate_mps = 0.2;     ///< how fast the output position may be moved by a correction
  double max_rate_radps = 0.05;  ///< ... and its orientation
};

class CorrectionSlew {
 public:
  explicit CorrectionSlew(const CorrectionSlewConfig& config = {});

  /// A new correction to follow (loop closure, or tracking in a saved map).
  void SetTarget(const Eigen::Isometry3d& T_map_odom);
  /// A correction to take at once: the first pose in a saved map (relocalization), before
  /// which nothing was published in the map frame.
  void JumpTo(const Eigen::Isometry3d& T_map_odom);
  /// Steps the correction toward the target for an output at `t_ns` of `T_odom_imu` and
  /// returns the correction to apply to it. Time going backwards (or the first call) does not
  /// move it.
  const Eigen::Isometry3d& Step(int64_t t_ns, const Eigen::Isometry3d& T_odom_imu);

  const Eigen::Isometry3d& current() const { return current_; }
  const Eigen::Isometry3d& target() const { return target_; }
  /// The current correction has reached the target.
  bool settled() const { return settled_; }

 private:
  CorrectionSlewConfig config_;
  Eigen::Isometry3d current_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d target_ = Eigen::Isometry3d::Identity();
  int64_t last_t_ns_ = 0;
  bool have_time_ = false;
  bool settled_ = true;
};

}  // namespace swlio::estimator
