#pragma once
/// @file
/// A smooth (C2) ground-robot trajectory: a planar path whose curvature is continuous (turns
/// are sin²-shaped curvature bumps), driven with a C1 speed profile (smoothstep speed changes),
/// lifted onto the terrain (height, roll and pitch from the driven surface).
///
/// The body frame is the IMU frame: x forward, y left, z up (normal to the driven surface).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "scenarios/chassis_vibration.h"

#include "world/terrain.h"

namespace swlio::sim {

/// One corner of a route: where the robot heads, with the radius of the turn there.
struct Waypoint {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  double turn_radius_m = 3.0;  ///< radius at the curvature peak of the turn at this waypoint
};

struct RouteSpec {
  std::vector<Waypoint> waypoints;  ///< ≥ 2; the robot starts at the first, stops at the last
  double cruise_speed_mps = 1.0;
  double max_yaw_rate_radps = 0.5;
  double max_lateral_acc_mps2 = 1.0;
  double mean_acc_mps2 = 0.3;  ///< of every speed change
  double stand_start_s = 2.0;  ///< standing still before moving
  double stand_end_s = 1.0;
  double imu_height_m = 0.6;  ///< IMU above the driven surface
};

/// Kinematic state of the body (IMU) frame at one instant.
struct Kinematics {
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_world_body = Eigen::Matrix3d::Identity();
  Eigen::Vector3d v_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d a_world = Eigen::Vector3d::Zero();     ///< without gravity
  Eigen::Vector3d omega_body = Eigen::Vector3d::Zero();  ///< rad/s in the body frame
};

class Trajectory {
 public:
  /// Builds the path and speed profile; `terrain` must outlive the trajectory.
  Trajectory(const RouteSpec& spec, const Terrain* terrain);

  double duration_s() const { return duration_s_; }
  /// Ends the timeline early (the robot simply stops being simulated at `duration_s`).
  void Truncate(double duration_s) { duration_s_ = std::min(duration_s_, duration_s); }
  double length_m() const { return length_m_; }  ///< of the route, driven once
  /// Path length driven in [0, duration_s()]: less than length_m() when Truncate cut the
  /// route, laps × length_m() after Repeat.
  double DrivenLengthM() const;
  /// Drives the route `laps` times, one lap every `period_s` (≥ the route's duration; the robot
  /// stands at the end until the next lap starts). Only meaningful for a route that ends where
  /// and as it starts (see EndsWhereItStarts); the duration becomes laps · period_s.
  void Repeat(int laps, double period_s);
  /// Whether the last pose is the first one (within 5 cm and 0.5°), so that laps join up.
  bool EndsWhereItStarts() const;
  double lap_period_s() const { return lap_period_s_; }  ///< 0: the route is driven once
  /// The route's kinematics at `t_s`, with the chassis vibration when one is set.
  Kinematics At(double t_s) const;
  /// Shakes the sensor head (the `vibration` disturbance); null: none.
  void SetVibration(std::shared_ptr<const ChassisVibration> vibration) {
    vibration_ = std::move(vibration);
  }
  const ChassisVibration* vibration() const { return vibration_.get(); }

 private:
  struct Segment {  ///< straight (theta = 0) or sin² turn
    double s0 = 0.0, length = 0.0, theta = 0.0, psi0 = 0.0;
  };
  struct Phase {  ///< speed v0 → v1 over duration (smoothstep), starting at t0, s0
    double t0 = 0.0, duration = 0.0, v0 = 0.0, v1 = 0.0, s0 = 0.0;
  };

  void BuildPath(const RouteSpec& spec);
  void BuildSpeedProfile(const RouteSpec& spec);
  void AddPhase(double duration, double v0, double v1);
  double Heading(double s) const;
  double Curvature(double s) const;
  Eigen::Vector2d Position(double s) const;
  /// Arc length, speed and tangential acceleration at time t.
  void SpeedAt(double t, double* s, double* v, double* a) const;
  Eigen::Matrix3d Attitude(const Eigen::Vector2d& xy, double psi) const;
  Kinematics AtInLap(double t_s) const;

  const Terrain* terrain_;
  double imu_height_m_ = 0.6;
  std::vector<Segment> segments_;
  std::vector<Eigen::Vector2d> table_xy_;  ///< path positions every kStep metres
  std::vector<Phase> phases_;
  std::vector<double> turn_speed_;  ///< per segment: speed while in it (turns), 0 for straights
  double length_m_ = 0.0;
  double duration_s_ = 0.0;
  double lap_period_s_ = 0.0;  ///< 0: one pass
  std::shared_ptr<const ChassisVibration> vibration_;
};

}  // namespace swlio::sim
