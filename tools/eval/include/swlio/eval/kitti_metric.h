#pragma once
/// @file
/// The KITTI odometry metric, as the KITTI devkit's evaluate_odometry.cpp computes it
/// (Geiger et al., CVPR 2012; devkit "devkit_odometry"):
/// - path distances d_k accumulated on the ground truth positions;
/// - for every first frame f = 0, step, 2·step, … and every length L in {100, …, 800} m: the
///   last frame l is the first with d_l > d_f + L (skip when none);
/// - error pose E = (P_f⁻¹ P_l)⁻¹ (G_f⁻¹ G_l) (G ground truth, P estimate, true inverses);
///   t_err = ‖E_t‖ / L, r_err = acos(clamp((tr(E_R) − 1)/2, −1, 1)) / L;
/// - the sequence figures are the means over all segments: translation in % (t_err·100) and
///   rotation in deg per 100 m (r_err·180/π·100).

#include "swlio/eval/trajectory.h"

#include <cstddef>
#include <vector>

namespace swlio::eval {

struct KittiOptions {
  std::size_t step_frames = 10;
  std::vector<double> lengths_m = {100, 200, 300, 400, 500, 600, 700, 800};
};

struct KittiSegment {
  std::size_t first_frame = 0;
  std::size_t last_frame = 0;
  double length_m = 0.0;
  double t_err_ratio = 0.0;  ///< translation error / length (m/m)
  double r_err_rad_per_m = 0.0;
};

struct KittiLengthSummary {
  double length_m = 0.0;
  std::size_t n = 0;
  double t_err_percent = 0.0;
  double r_err_deg_per_100m = 0.0;
};

struct KittiResult {
  std::vector<KittiSegment> segments;
  std::vector<KittiLengthSummary> per_length;  ///< one per length with n > 0
  double t_err_percent = 0.0;                  ///< mean over all segments
  double r_err_deg_per_100m = 0.0;
};

/// Throws EvalError when the sizes differ or no segment fits in the ground truth path.
KittiResult KittiOdometryMetric(const Trajectory& gt,
                                const Trajectory& est,
                                const KittiOptions& options = {});

}  // namespace swlio::eval
