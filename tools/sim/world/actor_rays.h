#pragma once
/// @file
/// The actors as the LiDAR sees them: per MSOP packet, the actors whose bounding sphere lies in
/// the packet's azimuth wedge (4.8° at 600 rpm) are picked once; per firing sequence their
/// poses are taken at its time (55.5 µs apart; the 16 lasers of a sequence are within 42 µs,
/// 0.2 mm at 5 m/s); per ray the nearest part box of those actors is hit if it is nearer than
/// the static world's hit.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "world/actors.h"
#include "world/world.h"

namespace swlio::sim {

class ActorRays {
 public:
  /// Picks the actors of `set` that a ray from `origin_m` with a horizontal direction between
  /// `dir_first_xy` and `dir_last_xy` (the packet's first and last firing, unit, the short way
  /// round) may hit within `max_range_m` during [t0_s, t1_s].
  void BeginPacket(const ActorSet& set,
                   double t0_s,
                   double t1_s,
                   const Eigen::Vector3d& origin_m,
                   const Eigen::Vector2d& dir_first_xy,
                   const Eigen::Vector2d& dir_last_xy,
                   double max_range_m);
  /// Poses of the picked actors at `t_s` (a firing sequence's time).
  void SetTime(double t_s);
  /// When an actor's part is hit nearer than `hit` (no hit: range < 0) along o + t·d, |d| = 1,
  /// replaces it (range, class, reflectivity) and sets `actor` (its id) and `moving`; else sets
  /// `actor` to 0 and leaves `hit` alone.
  void Cast(const Eigen::Vector3d& o,
            const Eigen::Vector3d& d,
            double max_range_m,
            RayHit* hit,
            uint16_t* actor,
            bool* moving) const;
  size_t candidates() const { return picked_.size(); }

 private:
  struct Picked {
    const Actor* actor = nullptr;
    bool moving = false;
    Eigen::Vector3d ground_m = Eigen::Vector3d::Zero();
    double cos_yaw = 1.0, sin_yaw = 0.0;
  };
  const ActorSet* set_ = nullptr;
  std::vector<Picked> picked_;
};

/// Entry distance (> 1e-6) of the ray o + t·d into the axis-aligned box `part` given in the
/// same frame, or +inf.
double IntersectPart(const ActorPart& part, const Eigen::Vector3d& o, const Eigen::Vector3d& d);

}  // namespace swlio::sim
