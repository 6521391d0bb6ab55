#pragma once
/// @file
/// The simulated world: analytic primitives (oriented boxes, finite cylinders, spheres) above a
/// Terrain, each with a class label (kept for tests) and a reflectivity, in a uniform 2-D grid
/// for ray casting.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "world/terrain.h"

namespace swlio::sim {

class ActorSet;

enum class SurfaceClass : uint8_t {
  kNone = 0,
  kGround,
  kWall,  ///< buildings
  kFence,
  kPole,
  kTransformer,
  kGantry,
  kInsulator,
  kBusbar,
  kTrench,  ///< cable-trench covers
  kTree,
  kPerson,   ///< a walking or standing person (world/actors.h)
  kVehicle,  ///< a maintenance van or pickup, driving or parked (world/actors.h)
};

const char* ClassName(SurfaceClass c);

/// Box with a vertical yaw axis: centre, half extents in its own frame, yaw about z.
struct Box {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d half_m = Eigen::Vector3d::Ones();
  double yaw_rad = 0.0;
};

/// Finite cylinder between two axis end points.
struct Cylinder {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::UnitZ();
  double radius_m = 0.1;
};

struct Sphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius_m = 1.0;
};

struct Primitive {
  enum class Kind : uint8_t { kBox, kCylinder, kSphere } kind = Kind::kBox;
  Box box;
  Cylinder cylinder;
  Sphere sphere;
  SurfaceClass cls = SurfaceClass::kWall;
  float reflectivity = 50.0f;                        ///< 0–255 as a LiDAR reports intensity
  Eigen::Vector2d min_xy = Eigen::Vector2d::Zero();  ///< footprint bounds, filled by World::Add
  Eigen::Vector2d max_xy = Eigen::Vector2d::Zero();
};

struct RayHit {
  double range_m = -1.0;  ///< < 0: no hit within the maximum range
  SurfaceClass cls = SurfaceClass::kNone;
  float reflectivity = 0.0f;
};

class World {
 public:
  Terrain terrain;
  float ground_reflectivity = 25.0f;
  Eigen::Vector2d bounds_min = Eigen::Vector2d::Zero();  ///< extent of the grid
  Eigen::Vector2d bounds_max = Eigen::Vector2d::Zero();
  /// People and vehicles moving through the world (null: none). Cast() sees only the static
  /// primitives; the LiDAR simulator adds the actors at each firing's time (actor_rays.h).
  std::shared_ptr<const ActorSet> actors;

  void AddBox(const Box& b, SurfaceClass cls, float reflectivity);
  void AddCylinder(const Cylinder& c, SurfaceClass cls, float reflectivity);
  void AddSphere(const Sphere& s, SurfaceClass cls, float reflectivity);

  /// Builds the acceleration grid; call after the last Add and before Cast.
  void Build(double cell_m = 4.0);

  /// Nearest hit of the ray o + t·d (|d| = 1) within (0, max_range_m].
  RayHit Cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range_m) const;

  const std::vector<Primitive>& primitives() const { return primitives_; }
  size_t CountOf(SurfaceClass cls) const;

 private:
  void Add(Primitive p);
  /// Nearest primitive hit among the grid cell's primitives, updating `best`.
  void CastCell(size_t cell,
                const Eigen::Vector3d& o,
                const Eigen::Vector3d& d,
                RayHit* best) const;

  std::vector<Primitive> primitives_;
  double cell_m_ = 4.0;
  int nx_ = 0;
  int ny_ = 0;
  std::vector<uint32_t> cell_start_;  ///< CSR offsets into cell_items_, size nx·ny + 1
  std::vector<uint32_t> cell_items_;
};

}  // namespace swlio::sim
