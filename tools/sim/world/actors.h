#pragma once
/// @file
/// People and vehicles in the substation ("actors", issue 36): rigid boxes that walk or drive
/// along straight legs between waypoints on the ground, with a trapezoidal speed profile on each
/// leg (accelerate, cruise, brake to a stop at the next waypoint), a turn in place and an
/// optional stop at each waypoint, standing at the first waypoint until their start time and at
/// the last one after it. Pose at any time: x, y on the ground, z from the terrain, yaw along
/// the leg. The parameters (speeds, sizes, where and when) are drawn elsewhere
/// (disturb/actor_setup.h); this file is the motion model only.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "world/terrain.h"
#include "world/world.h"

namespace swlio::sim {

enum class ActorKind : uint8_t { kPerson, kVehicle };

/// What an actor is there for (set up by disturb/actor_setup.cpp; kept for the manifest and
/// tests).
enum class ActorRole : uint8_t {
  kCrossing,        ///< a person crossing the robot's road in front of it
  kWalking,         ///< a person walking along a road edge, with a stop
  kInspecting,      ///< a person walking into a bay lane, standing there, walking back
  kOncoming,        ///< a vehicle meeting the robot in the other lane (maybe stopping before)
  kOvertaking,      ///< a vehicle passing the robot, stopping ahead of it, driving on
  kParkedLeaving,   ///< a vehicle parked beside the road that leaves while the robot is near
  kParkedAllDrive,  ///< a vehicle parked the whole drive (does not move)
};

const char* ActorKindName(ActorKind kind);

/// One rigid part of an actor's body, in the actor's frame (x forward along its path, y left,
/// z up, origin on the ground below the footprint's centre).
struct ActorPart {
  Eigen::Vector3d center_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d half_m = Eigen::Vector3d::Ones();
  float reflectivity = 40.0f;  ///< 0–255 as the LiDAR reports intensity
};

/// Everything that determines an actor's motion and body.
struct ActorPlan {
  ActorKind kind = ActorKind::kPerson;
  ActorRole role = ActorRole::kWalking;
  std::vector<Eigen::Vector2d> waypoints_xy;  ///< ≥ 1; consecutive ones distinct
  /// Standing time at each waypoint after arriving (and turning), same size as waypoints_xy;
  /// the first and last entries are unused (the actor stands there before t_go_s and after the
  /// end).
  std::vector<double> stop_s;
  double t_go_s = std::numeric_limits<double>::infinity();  ///< leaves the first waypoint
  double cruise_mps = 1.2;
  double acc_mps2 = 0.7;         ///< acceleration and braking on every leg
  double turn_rate_radps = 1.5;  ///< turning in place at a waypoint
  double yaw0_rad = 0.0;         ///< heading of an actor with one waypoint
  std::vector<ActorPart> parts;  ///< ≥ 1
};

/// Where an actor is at one instant.
struct ActorPose {
  Eigen::Vector3d ground_m = Eigen::Vector3d::Zero();  ///< frame origin, on the terrain
  double yaw_rad = 0.0;
  double speed_mps = 0.0;  ///< along its path (0 while turning in place)
};

class Actor {
 public:
  /// `terrain` must outlive the actor; `id` ≥ 1.
  Actor(uint16_t id, ActorPlan plan, const Terrain* terrain);

  ActorPose At(double t_s) const;
  /// The time it reaches waypoint `k` (t_go_s for k = 0).
  double ArrivalS(size_t k) const;
  /// The time it is `dist_m` along leg `leg` (from waypoint `leg` to the next one).
  double PassS(size_t leg, double dist_m) const;
  /// When it stops for the last time (t_go_s for an actor with one waypoint).
  double EndS() const;
  /// Whether it moves at some time in [t0_s, t1_s].
  bool MovesWithin(double t0_s, double t1_s) const;

  uint16_t id() const { return id_; }
  const ActorPlan& plan() const { return plan_; }
  SurfaceClass surface_class() const;
  /// The box around every part, in the actor's frame.
  const ActorPart& bounds() const { return bounds_; }
  /// Radius of the sphere around the frame origin that holds every part.
  double radius_m() const { return radius_m_; }

 private:
  struct Leg {  ///< straight from waypoint i to i + 1: trapezoidal speed profile
    double t0_s = 0.0, duration_s = 0.0, length_m = 0.0, v_peak_mps = 0.0, t_acc_s = 0.0;
    double yaw_rad = 0.0;
  };
  void BuildLegs();
  /// Distance along leg `leg` after `tau_s` on it, and the speed there.
  double LegDistance(const Leg& leg, double tau_s, double* speed_mps) const;
  ActorPose Standing(const Eigen::Vector2d& xy, double yaw_rad) const;

  uint16_t id_;
  ActorPlan plan_;
  const Terrain* terrain_;
  std::vector<Leg> legs_;
  ActorPart bounds_;
  double radius_m_ = 0.0;
};

/// Every actor of a drive, ids 1, 2, … in order.
class ActorSet {
 public:
  /// `terrain` must outlive the set; `drive_duration_s` decides which actors count as moving.
  ActorSet(const Terrain* terrain, double drive_duration_s);

  /// Adds an actor with the next id and returns it.
  const Actor& Add(ActorPlan plan);
  const std::vector<Actor>& actors() const { return actors_; }
  const Actor& Get(uint16_t id) const { return actors_[static_cast<size_t>(id) - 1]; }
  /// Whether actor `id` moves at some time during the drive (SimReturn::moving).
  bool Moving(uint16_t id) const;
  double drive_duration_s() const { return drive_duration_s_; }
  const Terrain* terrain() const { return terrain_; }

 private:
  const Terrain* terrain_;
  double drive_duration_s_;
  std::vector<Actor> actors_;
};

}  // namespace swlio::sim
