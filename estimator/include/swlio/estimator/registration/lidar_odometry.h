#pragma once
/// @file
/// LiDAR-only scan-to-map odometry: the LeGO-LOAM-like baseline of the tightly coupled
/// estimator. The IMU only predicts (initial guess) and de-skews; the pose comes from
/// registering each sweep's features against a local map of the previous sweeps' features.
///
/// Per sweep: propagate the IMU from the last corrected state to the sweep's end (one pose per
/// sample) → de-skew into the sweep-end LiDAR frame → front end (segmentation, edge/planar
/// features, voxel filter) → point-to-plane and point-to-line registration against the plane
/// and edge maps from the propagated guess → correct the state → insert the features into the
/// maps when the sweep is a keyframe. The corrected velocity is the propagated one plus the
/// position correction spread over the sweep period (the IMU cannot be trusted for more in this
/// mode). Initialization: standing still (StaticInitializer); sweeps before that are skipped. Pure
/// library: the caller supplies samples and sweeps in time order (host ns) and, for stage timings,
/// a clock.

#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <vector>

#include "swlio/core/types.h"
#include "swlio/estimator/common/estimator_config.h"
#include "swlio/estimator/common/stage_timer.h"
#include "swlio/estimator/frontend/front_end.h"
#include "swlio/estimator/imu/imu_propagator.h"
#include "swlio/estimator/init/static_initializer.h"
#include "swlio/estimator/registration/scan_matcher.h"
#include "swlio/estimator/registration/voxel_map.h"

namespace swlio::estimator {

struct LidarOdometryConfig {
  EstimatorConfig estimator;                                      ///< gravity, init, voxels
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();  ///< extrinsic
  FrontEndConfig front_end;
  ScanMatcherConfig matcher;
  /// Local maps: 0.5 m cells of at most 10 points at ≥ 0.1 m spacing keep a neighbour search
  /// within ~30 candidates (measured: 1 m cells of 20 were 2× slower for the same accuracy).
  VoxelMapConfig plane_map = {.voxel_m = 0.5, .max_points_per_voxel = 10};
  VoxelMapConfig edge_map = {.voxel_m = 0.5, .max_points_per_voxel = 10};
  size_t min_inliers = 100;  ///< fewer matched features: keep the IMU prediction
  /// A sweep becomes a keyframe (its features join the maps) after this much motion since the
  /// last keyframe; 0 inserts every sweep.
  double keyframe_distance_m = 0.2;
  double keyframe_angle_rad = 0.05;

  ConfigIssues Validate() const;
};

/// The odometry's options for a configuration's `estimator` section: its feature voxels
/// (plane_voxel_m, edge_voxel_m) go to the front end and its local_map_radius_m to both maps;
/// everything else keeps the defaults above.
LidarOdometryConfig MakeOdometryConfig(const EstimatorConfig& estimator,
                                       const Eigen::Isometry3d& T_imu_lidar);

enum class OdometryStatus {
  kInitializing,  ///< not yet initialized: the sweep was not used
  kTracking,      ///< registered against the map
  kMatchFailed,   ///< too few matched features: the IMU prediction was kept
  kSkipped,       ///< starts before the current state (out of order, overlap): not used
};

const char* ToString(OdometryStatus status);

struct OdometryResult {
  OdometryStatus status = OdometryStatus::kInitializing;
  State state;        ///< IMU state at the sweep's end (valid unless kInitializing)
  MatchResult match;  ///< registration details (degeneracy eigenvalues, inliers, …)
  size_t points_in = 0;
  size_t points_uncovered = 0;  ///< points the IMU track did not cover (left as measured)
  size_t planes = 0;            ///< planar features used
  size_t edges = 0;             ///< edge features used
  bool keyframe = false;        ///< its features were added to the local map
  StageTimes times;
};

class LidarOdometry {
 public:
  /// `now_ns` (optional) times the stages; the library reads no clock itself.
  explicit LidarOdometry(const LidarOdometryConfig& config, NowNsFn now_ns = nullptr);

  void AddImu(const ImuSample& sample);
  OdometryResult AddScan(const Scan& scan);

  bool initialized() const { return initialized_; }
  const VoxelMap& plane_map() const { return plane_map_; }
  const VoxelMap& edge_map() const { return edge_map_; }

 private:
  void PropagateTo(int64_t t_ns);
  void Correct(const Eigen::Isometry3d& T_world_lidar, int64_t t_ns);
  void InsertFeatures(const Eigen::Isometry3d& T_world_lidar);
  bool IsKeyframe(const Eigen::Isometry3d& T_world_lidar) const;

  LidarOdometryConfig config_;
  NowNsFn now_ns_;
  StaticInitializer initializer_;
  ImuPropagator propagator_;
  std::deque<ImuSample> pending_imu_;  ///< samples after the last propagated time
  FrontEnd front_end_;
  FrontEndOutput features_;
  Scan deskewed_;
  std::vector<Eigen::Vector3d> xyz_;
  std::vector<Eigen::Vector3d> planes_lidar_;
  std::vector<Eigen::Vector3d> edges_lidar_;
  VoxelMap plane_map_;
  VoxelMap edge_map_;
  ScanMatcher matcher_;
  bool initialized_ = false;
  bool have_keyframe_ = false;
  Eigen::Isometry3d T_world_last_keyframe_ = Eigen::Isometry3d::Identity();
};

}  // namespace swlio::estimator
