#include "terrain.h"

#include <cmath>
#include <numbers>

namespace swlio::sim {
namespace {

double WavesValue(const std::vector<Wave>& waves, const Eigen::Vector2d& p) {
  double h = 0.0;
  for (const Wave& w : waves) h += w.amplitude_m * std::sin(w.k.dot(p) + w.phase_rad);
  return h;
}

Eigen::Vector2d WavesGradient(const std::vector<Wave>& waves, const Eigen::Vector2d& p) {
  Eigen::Vector2d g = Eigen::Vector2d::Zero();
  for (const Wave& w : waves) g += w.amplitude_m * std::cos(w.k.dot(p) + w.phase_rad) * w.k;
  return g;
}

/// Bump profile value and its first two derivatives along `along`, zero outside.
struct Profile {
  double value = 0.0, d1 = 0.0, d2 = 0.0;
  Eigen::Vector2d along = Eigen::Vector2d::Zero();
};

Profile BumpProfile(const Bump& b, const Eigen::Vector2d& p) {
  // h(u) = H·cos⁴(πu / 2L): value, slope and curvature all vanish at |u| = L, so a robot
  // driving over it has continuous acceleration (C2 path).
  Profile out;
  const Eigen::Vector2d rel = p - b.center;
  const double u = rel.dot(b.along);
  const double v = rel.x() * -b.along.y() + rel.y() * b.along.x();
  if (std::abs(u) >= b.half_length_m || std::abs(v) >= b.half_width_m) return out;
  const double w = 0.5 * std::numbers::pi / b.half_length_m;
  const double c = std::cos(w * u), s = std::sin(w * u);
  out.value = b.height_m * c * c * c * c;
  out.d1 = -4.0 * b.height_m * w * c * c * c * s;
  out.d2 = b.height_m * w * w * (12.0 * c * c * s * s - 4.0 * c * c * c * c);
  out.along = b.along;
  return out;
}

}  // namespace

double Terrain::Height(const Eigen::Vector2d& p) const {
  double h = slope.dot(p) + WavesValue(undulations, p);
  for (const Bump& b : bumps) h += BumpProfile(b, p).value;
  return h;
}

Eigen::Vector2d Terrain::Gradient(const Eigen::Vector2d& p) const {
  Eigen::Vector2d g = slope + WavesGradient(undulations, p);
  for (const Bump& b : bumps) {
    const Profile pr = BumpProfile(b, p);
    g += pr.d1 * pr.along;
  }
  return g;
}

Eigen::Matrix2d Terrain::Hessian(const Eigen::Vector2d& p) const {
  Eigen::Matrix2d H = Eigen::Matrix2d::Zero();
  for (const Wave& w : undulations) {
    H -= w.amplitude_m * std::sin(w.k.dot(p) + w.phase_rad) * w.k * w.k.transpose();
  }
  for (const Bump& b : bumps) {
    const Profile pr = BumpProfile(b, p);
    H += pr.d2 * pr.along * pr.along.transpose();
  }
  return H;
}

double Terrain::SurfaceHeight(const Eigen::Vector2d& p) const {
  return Height(p) + WavesValue(roughness, p);
}

Eigen::Vector2d Terrain::SurfaceGradient(const Eigen::Vector2d& p) const {
  return Gradient(p) + WavesGradient(roughness, p);
}

double Terrain::Intersect(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_max) const {
  // Start from the tangent plane under the origin, then Newton on f(t) = z(t) − S(xy(t)).
  const Eigen::Vector2d o2 = o.head<2>();
  const Eigen::Vector2d d2 = d.head<2>();
  const double above = o.z() - SurfaceHeight(o2);
  if (above <= 0.0) return -1.0;
  const double closing = -d.z() + Gradient(o2).dot(d2);
  if (closing <= 1e-4) return -1.0;
  double t = above / closing;
  if (t > 2.0 * t_max) return -1.0;
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector2d p = o2 + t * d2;
    const double f = o.z() + t * d.z() - SurfaceHeight(p);
    if (std::abs(f) < 1e-5) return (t > 0.0 && t <= t_max) ? t : -1.0;
    const double df = d.z() - SurfaceGradient(p).dot(d2);
    if (df >= -1e-6) return -1.0;  // grazing: no stable intersection
    t -= f / df;
    if (t <= 0.0) return -1.0;
  }
  return -1.0;
}

}  // namespace swlio::sim
