#include "sensors/lidar_weather.h"

#include <algorithm>
#include <cmath>

namespace swlio::sim {
namespace {

constexpr double kMarshallPalmerN0 = 8000.0;  ///< m⁻³ mm⁻¹ (Marshall & Palmer 1948)

/// Λ (1/mm) of the Marshall–Palmer distribution at rain rate R (mm/h): 4.1·R^−0.21.
double MarshallPalmerLambda(double rate_mm_per_h) {
  return 4.1 * std::pow(std::max(rate_mm_per_h, 1e-3), -0.21);
}

/// `d` turned by `angle_rad` about the unit axis `u` (Rodrigues).
Eigen::Vector3d Turn(const Eigen::Vector3d& d, const Eigen::Vector3d& u, double angle_rad) {
  const double c = std::cos(angle_rad), s = std::sin(angle_rad);
  return c * d + s * u.cross(d) + (1.0 - c) * u.dot(d) * u;
}

bool IsJump(const MixedPixelConfig& m, double a_m, double b_m) {
  if (a_m <= 0.0 || b_m <= 0.0) return (a_m > 0.0) != (b_m > 0.0);
  return std::abs(a_m - b_m) > std::max(m.edge_jump_m, m.edge_jump_fraction * std::min(a_m, b_m));
}

/// Reflectivity 0–255 (as the LiDAR reports it: 0–100 diffuse %) as a fraction.
double Albedo(float reflectivity) { return static_cast<double>(reflectivity) / 100.0; }

/// Standard normal CDF.
double Phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

}  // namespace

double RainEchoesPerRay(const RainConfig& rain) {
  // ∫ A·n(D > D1·r) dr with n(D > x) = N0/Λ·exp(−Λ·x): A·N0/(Λ·k)·(e^{−k·a} − e^{−k·b}), k = Λ·D1.
  const double lambda = MarshallPalmerLambda(rain.rate_mm_per_h);
  const double k = lambda * rain.detect_diameter_at_1m_mm;
  const double a = rain.near_min_m, b = std::max(rain.near_max_m, rain.near_min_m);
  return rain.beam_area_m2 * kMarshallPalmerN0 / (lambda * k) *
         (std::exp(-k * a) - std::exp(-k * b));
}

double RainExtinctionPerM(const RainConfig& rain) {
  // α = 1.076·R^0.67 dB/km → 1/m: ·ln(10)/10/1000.
  return 1.076 * std::pow(rain.rate_mm_per_h, 0.67) * std::log(10.0) / 1e4;
}

double RainTransmission(const RainConfig& rain, double range_m) {
  return std::exp(-2.0 * RainExtinctionPerM(rain) * range_m);
}

double DetectionProbability(const DetectionConfig& d, double power) {
  if (power <= 0.0) return 0.0;
  const double reference = d.reference_reflectivity / (d.reference_range_m * d.reference_range_m);
  return 1.0 / (1.0 + std::pow(reference / power, d.steepness));
}

bool IsPuddle(const DetectionConfig& d, double x_m, double y_m) {
  const auto cx = static_cast<int64_t>(std::floor(x_m / d.puddle_cell_m));
  const auto cy = static_cast<int64_t>(std::floor(y_m / d.puddle_cell_m));
  return HashUniform(static_cast<uint64_t>(cx), static_cast<uint64_t>(cy), d.puddle_seed) <
         d.puddle_fraction;
}

LidarWeather::LidarWeather(const World* world, const LidarWeatherConfig& config, uint64_t seed)
    : world_(world), config_(config), rng_(seed ^ 0x3EA7E4ull) {
  previous_range_m_.fill(-1.0);
  if (config_.rain.on) {
    rain_echo_probability_ = 1.0 - std::exp(-RainEchoesPerRay(config_.rain));
    rain_decay_per_m_ =
        MarshallPalmerLambda(config_.rain.rate_mm_per_h) * config_.rain.detect_diameter_at_1m_mm;
    rain_alpha_per_m_ = RainExtinctionPerM(config_.rain);
  }
}

void LidarWeather::Apply(const WeatherRay& ray, double max_range_m, RayHit* hit) {
  ++counts_.rays;
  if (config_.mixed.on) ApplyMixedPixel(ray, max_range_m, hit);
  if (config_.rain.on && ApplyRain(hit)) return;
  if (config_.dust.on && ApplyDust(ray, hit)) return;
  if (config_.detection.on || config_.rain.on) ApplyDetection(ray, hit);
}

/// The footprint is a Gaussian spot of 1/e² radius w = divergence/2 (σ = w/2) in the scan
/// direction. Sub-rays at ±w find a surface other than the centre's; bisection places the edge
/// at offset e; the fraction 1 − Φ(e/σ) of the energy falls beyond it. The echoes merge into
/// one return at the power-weighted mean range, power ∝ fraction·ρ/r².
void LidarWeather::ApplyMixedPixel(const WeatherRay& ray, double max_range_m, RayHit* hit) {
  const MixedPixelConfig& m = config_.mixed;
  double& previous = previous_range_m_[static_cast<size_t>(ray.laser & 15)];
  const bool jump = IsJump(m, previous, hit->range_m);
  previous = hit->range_m;
  if (hit->range_m <= 0.0 || !(jump || m.every_ray)) return;
  ++counts_.edge_checks;
  const FootprintEdge edge = FindEdge(ray, max_range_m, *hit);
  counts_.sub_rays += static_cast<uint64_t>(edge.casts);
  if (!edge.found) return;
  const double w = 0.5 * m.divergence_rad;
  const RayHit& other = edge.other;
  const double beyond = 1.0 - Phi(edge.offset_rad / (0.5 * w));
  const double p_centre =
      (1.0 - beyond) * Albedo(hit->reflectivity) / (hit->range_m * hit->range_m);
  const double p_other = beyond * Albedo(other.reflectivity) / (other.range_m * other.range_m);
  if (p_other <= 0.0 || p_centre + p_other <= 0.0) return;
  hit->range_m = (p_centre * hit->range_m + p_other * other.range_m) / (p_centre + p_other);
  hit->reflectivity = static_cast<float>(
      (p_centre * hit->reflectivity + p_other * other.reflectivity) / (p_centre + p_other));
  if (p_other > p_centre) hit->cls = other.cls;
  ++counts_.mixed;
}

/// Casts the footprint's edges (±w about the rotation axis); where one of them sees another
/// surface (the larger range step if both do), four bisection casts place the edge to w/16.
LidarWeather::FootprintEdge LidarWeather::FindEdge(const WeatherRay& ray,
                                                   double max_range_m,
                                                   const RayHit& centre) const {
  const MixedPixelConfig& m = config_.mixed;
  const double w = 0.5 * m.divergence_rad;
  FootprintEdge edge;
  auto cast_at = [&](double offset_rad) {
    ++edge.casts;
    return world_->Cast(ray.origin_world, Turn(ray.dir_world, ray.up_world, offset_rad),
                        max_range_m);
  };
  double side = 0.0;
  for (const double s : {-1.0, 1.0}) {
    const RayHit h = cast_at(s * w);
    if (h.range_m > 0.0 && IsJump(m, centre.range_m, h.range_m) &&
        (side == 0.0 ||
         std::abs(h.range_m - centre.range_m) > std::abs(edge.other.range_m - centre.range_m))) {
      edge.other = h;
      side = s;
    }
  }
  if (side == 0.0) return edge;
  double inside = 0.0, outside = w;  // the edge lies between these offsets
  for (int i = 0; i < 4; ++i) {
    const double mid = 0.5 * (inside + outside);
    if (IsJump(m, centre.range_m, cast_at(side * mid).range_m)) {
      outside = mid;
    } else {
      inside = mid;
    }
  }
  edge.found = true;
  edge.offset_rad = 0.5 * (inside + outside);
  return edge;
}

/// A drop echo: the number of detectable drops along the beam is Poisson with mean
/// RainEchoesPerRay; the first one's range follows their density ∝ exp(−Λ·D1·r).
bool LidarWeather::ApplyRain(RayHit* hit) {
  const RainConfig& rain = config_.rain;
  if (rng_.Uniform() >= rain_echo_probability_) return false;
  const double a = rain.near_min_m, b = std::max(rain.near_max_m, rain.near_min_m);
  const double k = rain_decay_per_m_;
  const double r = a - std::log(1.0 - rng_.Uniform() * (1.0 - std::exp(-k * (b - a)))) / k;
  if (hit->range_m > 0.0 && hit->range_m < r) return false;  // behind the surface: unseen
  hit->range_m = r;
  hit->cls = SurfaceClass::kNone;
  hit->reflectivity = kAirborneReflectivity;
  ++counts_.rain;
  return true;
}

/// Inside an active puff the beam is scattered back at the first of Poisson events with rate
/// `extinction_per_m` along its path in the cloud; a beam that crosses the cloud is lost with
/// `loss_fraction`.
bool LidarWeather::ApplyDust(const WeatherRay& ray, RayHit* hit) {
  for (const DustPuff& puff : config_.dust.puffs) {
    if (ray.t_ns < puff.t_start_ns || ray.t_ns > puff.t_end_ns) continue;
    const double dt_s = static_cast<double>(ray.t_ns - puff.t_start_ns) * 1e-9;
    const Eigen::Vector3d c = puff.center_world + dt_s * puff.wind_world_mps;
    const Eigen::Vector3d w = ray.origin_world - c;
    const double b = w.dot(ray.dir_world);
    const double disc = b * b - (w.squaredNorm() - puff.radius_m * puff.radius_m);
    if (disc <= 0.0) continue;
    const double t_in = std::max(0.0, -b - std::sqrt(disc));
    double t_out = -b + std::sqrt(disc);
    if (hit->range_m > 0.0) t_out = std::min(t_out, hit->range_m);
    if (t_out <= t_in) continue;
    const double p_scatter = 1.0 - std::exp(-puff.extinction_per_m * (t_out - t_in));
    const double u = rng_.Uniform();
    if (u < p_scatter) {
      hit->range_m = t_in - std::log(1.0 - u) / puff.extinction_per_m;
      hit->cls = SurfaceClass::kNone;
      hit->reflectivity = kAirborneReflectivity;
      ++counts_.dust;
      return true;
    }
    if (rng_.Uniform() < puff.loss_fraction) {
      hit->range_m = -1.0;
      hit->cls = SurfaceClass::kNone;
      ++counts_.dust_lost;
      return true;
    }
  }
  return false;
}

/// Keeps a surface return with DetectionProbability of its power; with only rain on, with the
/// ratio of that probability with and without the rain's attenuation (the loss rain adds).
void LidarWeather::ApplyDetection(const WeatherRay& ray, RayHit* hit) {
  if (hit->range_m <= 0.0 || hit->cls == SurfaceClass::kNone) return;
  const DetectionConfig& d = config_.detection;
  double albedo = Albedo(hit->reflectivity);
  double cos_incidence = 1.0;  // primitives: normal incidence (their normals are not cast)
  if (d.on && hit->cls == SurfaceClass::kGround) {
    cos_incidence = std::max(std::abs(ray.dir_world.z()), 1e-3);  // the ground's normal ≈ z
    albedo *= d.wet_ground_factor;
    const Eigen::Vector3d p = ray.origin_world + hit->range_m * ray.dir_world;
    if (IsPuddle(d, p.x(), p.y())) albedo *= d.puddle_reflectivity_factor;
  }
  const double power = albedo * cos_incidence / (hit->range_m * hit->range_m);
  const double t2 = config_.rain.on ? std::exp(-2.0 * rain_alpha_per_m_ * hit->range_m) : 1.0;
  double p = DetectionProbability(d, power * t2);
  if (!d.on) p /= std::max(DetectionProbability(d, power), 1e-12);
  if (rng_.Uniform() < p) return;
  hit->range_m = -1.0;
  hit->cls = SurfaceClass::kNone;
  ++counts_.lost;
}

}  // namespace swlio::sim
