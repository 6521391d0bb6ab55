#include "world/terrain.h"

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

/// Adds the waves' value to `h` and their gradient to `g`, one sincos per wave (the ray caster's
/// Newton steps need both at the same point; separate sin and cos calls were 45 % of the
/// simulator's time, one sincos each cuts a 12 s drive's casting by a tenth).
void AddWaves(const std::vector<Wave>& waves,
              const Eigen::Vector2d& p,
              double* h,
              Eigen::Vector2d* g) {
  double value = 0.0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  for (const Wave& w : waves) {
    double s = 0.0, c = 0.0;
    ::sincos(w.k.dot(p) + w.phase_rad, &s, &c);  // glibc: the same values as sin and cos
    value += w.amplitude_m * s;
    gradient += w.amplitude_m * c * w.k;
  }
  *h += value;
  *g += gradient;
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

void Terrain::SurfaceHeightAndGradient(const Eigen::Vector2d& p,
                                       double* h,
                                       Eigen::Vector2d* g) const {
  // Summed in SurfaceHeight's and SurfaceGradient's order: the same values to the last bit.
  *h = slope.dot(p);
  *g = slope;
  AddWaves(undulations, p, h, g);
  for (const Bump& b : bumps) {
    const Profile pr = BumpProfile(b, p);
    *h += pr.value;
    *g += pr.d1 * pr.along;
  }
  AddWaves(roughness, p, h, g);
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
    double height = 0.0;
    Eigen::Vector2d gradient;
    SurfaceHeightAndGradient(o2 + t * d2, &height, &gradient);
    const double f = o.z() + t * d.z() - height;
    if (std::abs(f) < 1e-5) return (t > 0.0 && t <= t_max) ? t : -1.0;
    const double df = d.z() - gradient.dot(d2);
    if (df >= -1e-6) return -1.0;  // grazing: no stable intersection
    t -= f / df;
    if (t <= 0.0) return -1.0;
  }
  return -1.0;
}

}  // namespace swlio::sim
