#pragma once
/// @file
/// Where an actor may go: its footprint (the box around its body seen from above, grown by a
/// margin) must never overlap a static primitive that reaches into its height, another actor's
/// footprint, or come nearer to the robot than kRobotClearanceM. Checked on samples of its
/// motion (every 0.25 m and 0.1 rad) and of the drive (every 0.05 s).

#include <Eigen/Core>
#include <vector>

#include "scenarios/trajectory.h"
#include "world/actors.h"
#include "world/world.h"

namespace swlio::sim {

/// An oriented rectangle on the ground.
struct Footprint {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d half_m = Eigen::Vector2d::Ones();
  double yaw_rad = 0.0;
};

/// The actor's footprint at `pose`, each half size grown by `margin_m`.
Footprint FootprintAt(const Actor& actor, const ActorPose& pose, double margin_m = 0.0);
bool Overlap(const Footprint& a, const Footprint& b);
/// Distance from `p` to the rectangle (0 inside).
double Distance(const Eigen::Vector2d& p, const Footprint& f);

/// Robot centre (the IMU, above the axle midpoint) to the nearest point of an actor's body,
/// seen from above: at least this much at every instant (the robot is about 0.9 m across, so
/// half a metre stays free between them).
inline constexpr double kRobotClearanceM = 1.0;

/// The robot's position every `dt_s` of the drive.
struct RobotTrack {
  double dt_s = 0.05;
  std::vector<Eigen::Vector2d> xy;
};
RobotTrack SampleRobot(const Trajectory& trajectory, double dt_s = 0.05);

/// Smallest distance from the robot's centre to the actor's footprint over the drive, with the
/// time it happens.
double MinRobotDistanceM(const Actor& actor, const RobotTrack& robot, double* at_s = nullptr);

class ActorClearance {
 public:
  /// `world` and `robot` must outlive the checker.
  ActorClearance(const World* world, const RobotTrack* robot);

  /// Clear of every static primitive along its whole motion (margin: 0.15 m for people,
  /// 0.3 m for vehicles).
  bool ClearOfWorld(const Actor& actor) const;
  /// Never nearer to the robot than kRobotClearanceM.
  bool ClearOfRobot(const Actor& actor) const;
  /// Clear of every actor of `set` at every time (both footprints grown by 0.2 m).
  bool ClearOfActors(const Actor& actor, const ActorSet& set) const;

 private:
  struct Obstacle {
    Eigen::Vector2d min_xy, max_xy;
    double z_min = 0.0, z_max = 0.0;
  };
  const World* world_;
  const RobotTrack* robot_;
  std::vector<Obstacle> obstacles_;
};

}  // namespace swlio::sim
