#include "world/world.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swlio::sim {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Slab test in the box frame; returns the entry distance (> 0) or kInf.
double IntersectBox(const Box& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const double c = std::cos(b.yaw_rad);
  const double s = std::sin(b.yaw_rad);
  const Eigen::Vector3d r = o - b.center;
  const Eigen::Vector3d ol(c * r.x() + s * r.y(), -s * r.x() + c * r.y(), r.z());
  const Eigen::Vector3d dl(c * d.x() + s * d.y(), -s * d.x() + c * d.y(), d.z());
  double t0 = -kInf;
  double t1 = kInf;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(dl(i)) < 1e-12) {
      if (std::abs(ol(i)) > b.half_m(i)) return kInf;
      continue;
    }
    double ta = (-b.half_m(i) - ol(i)) / dl(i);
    double tb = (b.half_m(i) - ol(i)) / dl(i);
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return kInf;
  }
  return t0 > 1e-6 ? t0 : kInf;  // rays starting inside a box see nothing of it
}

/// Finite cylinder with flat caps; returns the entry distance (> 0) or kInf.
double IntersectCylinder(const Cylinder& cy, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const Eigen::Vector3d axis = cy.b - cy.a;
  const double len = axis.norm();
  const Eigen::Vector3d u = axis / len;
  const Eigen::Vector3d w = o - cy.a;
  const Eigen::Vector3d dp = d - d.dot(u) * u;
  const Eigen::Vector3d wp = w - w.dot(u) * u;
  const double A = dp.squaredNorm();
  const double B = 2.0 * dp.dot(wp);
  const double C = wp.squaredNorm() - cy.radius_m * cy.radius_m;
  double best = kInf;
  if (A > 1e-14) {
    const double disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
      const double t = (-B - std::sqrt(disc)) / (2.0 * A);
      const double h = w.dot(u) + t * d.dot(u);
      if (t > 1e-6 && h >= 0.0 && h <= len) best = t;
    }
  }
  const double du = d.dot(u);
  if (std::abs(du) > 1e-12) {  // caps
    for (const double h : {0.0, len}) {
      const double t = (h - w.dot(u)) / du;
      if (t > 1e-6 && t < best && (wp + t * dp).squaredNorm() <= cy.radius_m * cy.radius_m) {
        best = t;
      }
    }
  }
  return best;
}

double IntersectSphere(const Sphere& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const Eigen::Vector3d w = o - s.center;
  const double b = w.dot(d);
  const double c = w.squaredNorm() - s.radius_m * s.radius_m;
  const double disc = b * b - c;
  if (disc < 0.0) return kInf;
  const double t = -b - std::sqrt(disc);
  return t > 1e-6 ? t : kInf;
}

double IntersectPrimitive(const Primitive& p, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  switch (p.kind) {
    case Primitive::Kind::kBox:
      return IntersectBox(p.box, o, d);
    case Primitive::Kind::kCylinder:
      return IntersectCylinder(p.cylinder, o, d);
    case Primitive::Kind::kSphere:
      return IntersectSphere(p.sphere, o, d);
  }
  return kInf;
}

}  // namespace

const char* ClassName(SurfaceClass c) {
  switch (c) {
    case SurfaceClass::kNone:
      return "none";
    case SurfaceClass::kGround:
      return "ground";
    case SurfaceClass::kWall:
      return "wall";
    case SurfaceClass::kFence:
      return "fence";
    case SurfaceClass::kPole:
      return "pole";
    case SurfaceClass::kTransformer:
      return "transformer";
    case SurfaceClass::kGantry:
      return "gantry";
    case SurfaceClass::kInsulator:
      return "insulator";
    case SurfaceClass::kBusbar:
      return "busbar";
    case SurfaceClass::kTrench:
      return "trench";
    case SurfaceClass::kTree:
      return "tree";
    case SurfaceClass::kPerson:
      return "person";
    case SurfaceClass::kVehicle:
      return "vehicle";
  }
  return "unknown";
}

void World::Add(Primitive p) { primitives_.push_back(std::move(p)); }

void World::AddBox(const Box& b, SurfaceClass cls, float reflectivity) {
  Primitive p;
  p.kind = Primitive::Kind::kBox;
  p.box = b;
  p.cls = cls;
  p.reflectivity = reflectivity;
  const double c = std::abs(std::cos(b.yaw_rad));
  const double s = std::abs(std::sin(b.yaw_rad));
  const Eigen::Vector2d ext(c * b.half_m.x() + s * b.half_m.y(),
                            s * b.half_m.x() + c * b.half_m.y());
  p.min_xy = b.center.head<2>() - ext;
  p.max_xy = b.center.head<2>() + ext;
  Add(std::move(p));
}

void World::AddCylinder(const Cylinder& cy, SurfaceClass cls, float reflectivity) {
  Primitive p;
  p.kind = Primitive::Kind::kCylinder;
  p.cylinder = cy;
  p.cls = cls;
  p.reflectivity = reflectivity;
  const Eigen::Vector2d r = Eigen::Vector2d::Constant(cy.radius_m);
  p.min_xy = cy.a.head<2>().cwiseMin(cy.b.head<2>()) - r;
  p.max_xy = cy.a.head<2>().cwiseMax(cy.b.head<2>()) + r;
  Add(std::move(p));
}

void World::AddSphere(const Sphere& s, SurfaceClass cls, float reflectivity) {
  Primitive p;
  p.kind = Primitive::Kind::kSphere;
  p.sphere = s;
  p.cls = cls;
  p.reflectivity = reflectivity;
  p.min_xy = s.center.head<2>() - Eigen::Vector2d::Constant(s.radius_m);
  p.max_xy = s.center.head<2>() + Eigen::Vector2d::Constant(s.radius_m);
  Add(std::move(p));
}

void World::Build(double cell_m) {
  cell_m_ = cell_m;
  nx_ = static_cast<int>(std::ceil((bounds_max.x() - bounds_min.x()) / cell_m)) + 1;
  ny_ = static_cast<int>(std::ceil((bounds_max.y() - bounds_min.y()) / cell_m)) + 1;
  const size_t cells = static_cast<size_t>(nx_) * static_cast<size_t>(ny_);
  std::vector<std::vector<uint32_t>> lists(cells);
  for (size_t i = 0; i < primitives_.size(); ++i) {
    const Primitive& p = primitives_[i];
    const int x0 =
        std::clamp(static_cast<int>((p.min_xy.x() - bounds_min.x()) / cell_m), 0, nx_ - 1);
    const int x1 =
        std::clamp(static_cast<int>((p.max_xy.x() - bounds_min.x()) / cell_m), 0, nx_ - 1);
    const int y0 =
        std::clamp(static_cast<int>((p.min_xy.y() - bounds_min.y()) / cell_m), 0, ny_ - 1);
    const int y1 =
        std::clamp(static_cast<int>((p.max_xy.y() - bounds_min.y()) / cell_m), 0, ny_ - 1);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        lists[static_cast<size_t>(y) * static_cast<size_t>(nx_) + static_cast<size_t>(x)].push_back(
            static_cast<uint32_t>(i));
      }
    }
  }
  cell_start_.assign(cells + 1, 0);
  cell_items_.clear();
  for (size_t c = 0; c < cells; ++c) {
    cell_start_[c] = static_cast<uint32_t>(cell_items_.size());
    cell_items_.insert(cell_items_.end(), lists[c].begin(), lists[c].end());
  }
  cell_start_[cells] = static_cast<uint32_t>(cell_items_.size());
}

void World::CastCell(size_t cell,
                     const Eigen::Vector3d& o,
                     const Eigen::Vector3d& d,
                     RayHit* best) const {
  for (uint32_t k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
    const Primitive& p = primitives_[cell_items_[k]];
    const double t = IntersectPrimitive(p, o, d);
    if (t < best->range_m) {
      best->range_m = t;
      best->cls = p.cls;
      best->reflectivity = p.reflectivity;
    }
  }
}

RayHit World::Cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range_m) const {
  RayHit best;
  best.range_m = kInf;
  const double tg = terrain.Intersect(o, d, max_range_m);
  if (tg > 0.0) {
    best.range_m = tg;
    best.cls = SurfaceClass::kGround;
    best.reflectivity = ground_reflectivity;
  }
  // 2-D DDA over the grid cells the ray's footprint crosses, nearest first.
  const double gx = (o.x() - bounds_min.x()) / cell_m_;
  const double gy = (o.y() - bounds_min.y()) / cell_m_;
  int cx = static_cast<int>(std::floor(gx));
  int cy = static_cast<int>(std::floor(gy));
  const int step_x = d.x() >= 0.0 ? 1 : -1;
  const int step_y = d.y() >= 0.0 ? 1 : -1;
  const double inv_x = std::abs(d.x()) > 1e-12 ? 1.0 / std::abs(d.x()) : kInf;
  const double inv_y = std::abs(d.y()) > 1e-12 ? 1.0 / std::abs(d.y()) : kInf;
  double t_next_x = (step_x > 0 ? (cx + 1 - gx) : (gx - cx)) * cell_m_ * inv_x;
  double t_next_y = (step_y > 0 ? (cy + 1 - gy) : (gy - cy)) * cell_m_ * inv_y;
  const double dt_x = cell_m_ * inv_x;
  const double dt_y = cell_m_ * inv_y;
  double t_cell_start = 0.0;
  const double t_limit = std::min(max_range_m, best.range_m);
  while (t_cell_start <= std::min(t_limit, best.range_m)) {
    if (cx >= 0 && cy >= 0 && cx < nx_ && cy < ny_) {
      CastCell(static_cast<size_t>(cy) * static_cast<size_t>(nx_) + static_cast<size_t>(cx), o, d,
               &best);
    }
    if (t_next_x < t_next_y) {
      t_cell_start = t_next_x;
      t_next_x += dt_x;
      cx += step_x;
    } else {
      t_cell_start = t_next_y;
      t_next_y += dt_y;
      cy += step_y;
    }
    if (!std::isfinite(t_cell_start)) break;  // vertical ray: one cell only
  }
  if (best.range_m > max_range_m) best = RayHit{};
  return best;
}

size_t World::CountOf(SurfaceClass cls) const {
  return static_cast<size_t>(std::count_if(primitives_.begin(), primitives_.end(),
                                           [cls](const Primitive& p) { return p.cls == cls; }));
}

}  // namespace swlio::sim
