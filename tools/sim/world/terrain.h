#pragma once
/// @file
/// The substation's ground: a gently sloped surface with slow undulations and road bumps (what
/// the robot drives on, smooth with analytic derivatives) plus gravel roughness (what the LiDAR
/// also sees, a few centimetres of high-frequency relief).

#include <Eigen/Core>
#include <vector>

namespace swlio::sim {

/// One sinusoid A·sin(k·p + φ) of the height field.
struct Wave {
  Eigen::Vector2d k = Eigen::Vector2d::Zero();  ///< wave vector, rad/m
  double amplitude_m = 0.0;
  double phase_rad = 0.0;
};

/// A raised strip across a road (cable cover, speed bump): cos⁴ profile along `along`.
struct Bump {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  Eigen::Vector2d along = Eigen::Vector2d::UnitX();  ///< unit, direction of travel over it
  double half_length_m = 0.5;                        ///< profile half-length along travel
  double half_width_m = 3.0;                         ///< lateral extent
  double height_m = 0.06;
};

class Terrain {
 public:
  Eigen::Vector2d slope = Eigen::Vector2d::Zero();  ///< dz/dx, dz/dy
  std::vector<Wave> undulations;                    ///< slow, part of the driven surface
  std::vector<Bump> bumps;                          ///< part of the driven surface
  std::vector<Wave> roughness;                      ///< gravel, seen by the LiDAR only

  /// Driven (smooth) height, metres.
  double Height(const Eigen::Vector2d& p) const;
  Eigen::Vector2d Gradient(const Eigen::Vector2d& p) const;
  Eigen::Matrix2d Hessian(const Eigen::Vector2d& p) const;

  /// Height of the visible surface (driven height + gravel roughness).
  double SurfaceHeight(const Eigen::Vector2d& p) const;
  Eigen::Vector2d SurfaceGradient(const Eigen::Vector2d& p) const;
  /// Both at once (what the ray caster needs), equal to the two above to the last bit.
  void SurfaceHeightAndGradient(const Eigen::Vector2d& p, double* h, Eigen::Vector2d* g) const;

  /// First intersection of the ray o + t·d (|d| = 1) with the visible surface in (0, t_max];
  /// returns t, or a negative value when there is none (or Newton did not converge).
  double Intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_max) const;
};

}  // namespace swlio::sim
