#include "world/substation.h"

#include <cmath>
#include <numbers>

#include "rng.h"

namespace swlio::sim {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using L = Layout;

// Reflectivities (0–255) by material, roughly as RS16 reports them.
constexpr float kConcrete = 60.0f, kMetal = 110.0f, kPorcelain = 80.0f, kWood = 40.0f;
constexpr float kFoliage = 20.0f, kMesh = 35.0f;

double Ground(const World& w, double x, double y) { return w.terrain.Height(Vector2d(x, y)); }

/// Box standing on the ground at (x, y) with footprint half sizes and height.
void StandingBox(World& w,
                 double x,
                 double y,
                 double hx,
                 double hy,
                 double height,
                 double yaw,
                 SurfaceClass cls,
                 float refl) {
  const double z0 = Ground(w, x, y) - 0.1;  // sunk a little: no gap on slopes
  w.AddBox({Vector3d(x, y, z0 + 0.5 * height), Vector3d(hx, hy, 0.5 * height), yaw}, cls, refl);
}

void StandingCylinder(World& w,
                      double x,
                      double y,
                      double r,
                      double z_from_ground,
                      double z_to_ground,
                      SurfaceClass cls,
                      float refl) {
  const double g = Ground(w, x, y);
  w.AddCylinder({Vector3d(x, y, g + z_from_ground), Vector3d(x, y, g + z_to_ground), r}, cls, refl);
}

void MakeTerrain(Terrain& t, Rng& rng) {
  t.slope = Vector2d(rng.Uniform(-0.008, 0.008), rng.Uniform(-0.008, 0.008));
  for (int i = 0; i < 3; ++i) {
    const double wavelength = rng.Uniform(35.0, 90.0);
    const double dir = rng.Uniform(0.0, 2.0 * std::numbers::pi);
    t.undulations.push_back(
        {Vector2d(std::cos(dir), std::sin(dir)) * 2.0 * std::numbers::pi / wavelength,
         rng.Uniform(0.04, 0.12), rng.Uniform(0.0, 6.3)});
  }
  for (int i = 0; i < 5; ++i) {
    const double wavelength = rng.Uniform(0.35, 2.5);
    const double dir = rng.Uniform(0.0, 2.0 * std::numbers::pi);
    t.roughness.push_back(
        {Vector2d(std::cos(dir), std::sin(dir)) * 2.0 * std::numbers::pi / wavelength,
         rng.Uniform(0.002, 0.006), rng.Uniform(0.0, 6.3)});
  }
  // Bumps across the roads (cable covers): fixed places, seeded heights.
  const Vector2d ex = Vector2d::UnitX(), ey = Vector2d::UnitY();
  const std::pair<Vector2d, Vector2d> spots[] = {{{120.0, L::kRoadSouth}, ex},
                                                 {{L::kRoadEast, 40.0}, ey},
                                                 {{100.0, L::kRoadMiddle}, ex},
                                                 {{L::kRoadWest, 90.0}, ey},
                                                 {{150.0, L::kRoadNorth}, ex}};
  for (const auto& [c, along] : spots) {
    t.bumps.push_back({c, along, 0.5, 3.5, rng.Uniform(0.03, 0.06)});
  }
}

void MakeFence(World& w) {
  const Vector2d corners[] = {{L::kFenceMinX, L::kFenceMinY},
                              {L::kFenceMaxX, L::kFenceMinY},
                              {L::kFenceMaxX, L::kFenceMaxY},
                              {L::kFenceMinX, L::kFenceMaxY}};
  for (int i = 0; i < 4; ++i) {
    const Vector2d a = corners[i], b = corners[(i + 1) % 4];
    const Vector2d mid = 0.5 * (a + b);
    const double len = (b - a).norm();
    const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x());
    StandingBox(w, mid.x(), mid.y(), 0.5 * len, 0.02, 2.3, yaw, SurfaceClass::kFence, kMesh);
    const int posts = static_cast<int>(len / 3.0);
    for (int k = 0; k <= posts; ++k) {
      const Vector2d p = a + (b - a) * (static_cast<double>(k) / posts);
      const Vector2d n(-std::sin(yaw), std::cos(yaw));  // posts stand inside the mesh
      const Vector2d q = p + 0.08 * n;
      StandingCylinder(w, q.x(), q.y(), 0.04, -0.1, 2.5, SurfaceClass::kFence, kMetal);
    }
  }
}

void MakeBuildings(World& w, Rng& rng) {
  StandingBox(w, 15.0, 119.0, 15.0, 7.0, rng.Uniform(5.5, 7.0), 0.0, SurfaceClass::kWall,
              kConcrete);
  StandingBox(w, 33.0, 126.0, 3.0, 4.0, 3.2, 0.0, SurfaceClass::kWall, kConcrete);  // annex
}

void MakeTransformerBay(World& w, Rng& rng, double cx, double cy) {
  const double hx = rng.Uniform(2.2, 3.0), hy = rng.Uniform(1.5, 2.0), h = rng.Uniform(3.0, 4.0);
  StandingBox(w, cx, cy, hx, hy, h, 0.0, SurfaceClass::kTransformer, kMetal);
  for (int fin = -3; fin <= 3; ++fin) {  // radiator fins on the east side
    StandingBox(w, cx + hx + 0.35, cy + 0.45 * fin, 0.35, 0.04, h * 0.8, 0.0,
                SurfaceClass::kTransformer, kMetal);
  }
  for (int b = -1; b <= 1; ++b) {  // bushings on top
    const double g = Ground(w, cx + b * 1.2, cy);
    w.AddCylinder(
        {Vector3d(cx + b * 1.2, cy, g + h - 0.2), Vector3d(cx + b * 1.2, cy, g + h + 1.6), 0.18},
        SurfaceClass::kInsulator, kPorcelain);
  }
  StandingBox(w, cx - hx - 2.0, cy, 0.15, hy + 1.5, 6.0, 0.0, SurfaceClass::kWall, kConcrete);
}

void MakeSwitchgearBay(World& w, Rng& rng, double cx, double cy) {
  const int rows = 2 + static_cast<int>(rng.Below(2));
  for (int r = 0; r < rows; ++r) {
    for (int phase = -1; phase <= 1; ++phase) {
      const double x = cx - 6.0 + 6.0 * r + rng.Uniform(-0.3, 0.3);
      const double y = cy + 3.0 * phase;
      StandingCylinder(w, x, y, 0.16, -0.1, 2.5, SurfaceClass::kPole, kConcrete);  // pedestal
      StandingCylinder(w, x, y, 0.13, 2.5, 4.6, SurfaceClass::kInsulator, kPorcelain);
    }
  }
}

/// Gantry over a bay: two lattice columns on each y-edge, a beam across, three busbars.
void MakeGantry(World& w, double x0, double x1, double y0, double y1, double height) {
  for (const double y : {y0, y1}) {
    for (const double x : {x0, x1}) {
      StandingBox(w, x, y, 0.35, 0.35, height, 0.0, SurfaceClass::kGantry, kMetal);
    }
    const double z = 0.5 * (Ground(w, x0, y) + Ground(w, x1, y)) + height - 0.5;
    w.AddBox({Vector3d(0.5 * (x0 + x1), y, z), Vector3d(0.5 * (x1 - x0), 0.3, 0.5), 0.0},
             SurfaceClass::kGantry, kMetal);
  }
  for (int phase = -1; phase <= 1; ++phase) {
    const double x = 0.5 * (x0 + x1) + 2.5 * phase;
    const double z = Ground(w, x, 0.5 * (y0 + y1)) + height - 2.0;
    w.AddCylinder({Vector3d(x, y0, z), Vector3d(x, y1, z), 0.05}, SurfaceClass::kBusbar, kMetal);
  }
}

void MakeBays(World& w, Rng& rng) {
  const double row_y[2][2] = {{L::kRoadSouth + 6.0, L::kRoadMiddle - 6.0},
                              {L::kRoadMiddle + 6.0, L::kRoadNorth - 6.0}};
  for (const auto& row : row_y) {
    for (int k = 0; k < 5; ++k) {
      const double x0 = 51.0 + 28.0 * k, x1 = x0 + 22.0;
      const double cx = 0.5 * (x0 + x1), cy = 0.5 * (row[0] + row[1]);
      if (rng.Uniform() < 0.45) {
        MakeTransformerBay(w, rng, cx, cy);
      } else {
        MakeSwitchgearBay(w, rng, cx, cy);
      }
      MakeGantry(w, x0 + 1.0, x1 - 1.0, row[0] + 2.0, row[1] - 2.0, rng.Uniform(10.0, 12.0));
    }
  }
}

void MakePolesTrenchesTrees(World& w, Rng& rng) {
  for (double x = 55.0; x < 190.0; x += 20.0) {  // lighting poles outside the ring road
    StandingCylinder(w, x, L::kRoadSouth - 5.5, 0.12, -0.1, 8.0, SurfaceClass::kPole, kMetal);
    StandingCylinder(w, x + 10.0, L::kRoadNorth + 5.5, 0.12, -0.1, 8.0, SurfaceClass::kPole,
                     kMetal);
  }
  for (double y = 20.0; y < 112.0; y += 18.0) {
    StandingCylinder(w, L::kRoadEast + 5.5, y, 0.12, -0.1, 8.0, SurfaceClass::kPole, kMetal);
  }
  for (const double side : {-1.0, 1.0}) {  // trench covers along the middle road
    const double y = L::kRoadMiddle + side * 4.8;
    for (double x = 52.0; x < 188.0; x += 8.0) {
      StandingBox(w, x + 3.9, y, 3.9, 0.45, 0.22, 0.0, SurfaceClass::kTrench, kConcrete);
    }
  }
  for (double x = 48.0; x < 200.0; x += rng.Uniform(6.0, 12.0)) {
    const double y = rng.Uniform(127.0, 132.0);
    const double crown = rng.Uniform(1.5, 2.6);
    StandingCylinder(w, x, y, 0.2, -0.1, 3.0, SurfaceClass::kTree, kWood);
    w.AddSphere({Vector3d(x, y, Ground(w, x, y) + 3.0 + crown * 0.8), crown}, SurfaceClass::kTree,
                kFoliage);
  }
}

}  // namespace

World GenerateSubstation(uint64_t seed) {
  Rng rng(seed ^ 0x5B57A710ull);
  World w;
  w.bounds_min = Vector2d(L::kFenceMinX - 5.0, L::kFenceMinY - 5.0);
  w.bounds_max = Vector2d(L::kFenceMaxX + 5.0, L::kFenceMaxY + 5.0);
  MakeTerrain(w.terrain, rng);
  MakeFence(w);
  MakeBuildings(w, rng);
  MakeBays(w, rng);
  MakePolesTrenchesTrees(w, rng);
  w.Build(4.0);
  return w;
}

}  // namespace swlio::sim
