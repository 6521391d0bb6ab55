#pragma once
/// @file
/// What weather, edges and dark or wet surfaces do to the RS-LiDAR-16's returns (issue 36):
/// mixed pixels at depth discontinuities, spurious near returns from rain drops and dust, and
/// beams lost on dark, far or wet surfaces. Each model is off by default; with all off a
/// simulated LiDAR casts exactly as before. Magnitudes and their sources: tools/sim/README.md,
/// "Weather, edges and temperature", and the comments at each default.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "rng.h"
#include "world/world.h"

namespace swlio::sim {

/// Mixed pixels: the beam's footprint straddles a near and a far surface and the return lands
/// between them (Herbert & Krotkov 1992; Chaudhry, Salido-Monzú & Wieser, Remote Sensing 2021,
/// 13(4) 615; Hesai's manuals call them "interstitial points": "when a beam partially hits on a
/// front target's edge and further hits on a rear target, the return signal can result in a
/// false point located between both targets", PandarXT32M2X user manual, p. 58).
struct MixedPixelConfig {
  bool on = false;
  /// Full beam divergence in the scan direction, 1/e² (rad). 3.0 mrad horizontal (1.5 mrad
  /// vertical): Velodyne VLS-128 user manual, Appendix F, Table F-1, the same 905 nm spinning
  /// design; the RS-LiDAR-16's own figure was not found in the sources reachable here.
  double divergence_rad = 3.0e-3;
  /// A range jump against the same laser's previous firing larger than this (m, or this
  /// fraction of the range) marks a possible edge; only then are sub-rays cast.
  double edge_jump_m = 0.3;
  double edge_jump_fraction = 0.05;
  /// Cast the footprint's sub-rays for every firing instead of only after a jump (the full
  /// test; slower, for measuring what the cheap test misses).
  bool every_ray = false;
};

/// Rain: drops in the first metres give spurious returns; the drops along the path attenuate
/// every echo (a longer path loses more). The range of a surface return is not disturbed
/// (Filgueira et al., Measurement 2017, "Quantifying the influence of rain in LiDAR
/// performance", VLP-16: range variations below 20 cm, attributed to the procedure; intensity
/// and the number of points fall with the rain rate).
struct RainConfig {
  bool on = false;
  double rate_mm_per_h = 5.0;  ///< moderate rain (AMS Glossary: 2.6–7.6 mm/h)
  /// Drops are counted from the Marshall–Palmer size distribution N(D) = N0·exp(−Λ·D),
  /// N0 = 8000 m⁻³ mm⁻¹, Λ = 4.1·R^−0.21 mm⁻¹ (Marshall & Palmer, J. Meteorology 1948, 5, 165).
  /// A drop at range r gives a detectable echo when its diameter exceeds
  /// `detect_diameter_at_1m_mm`·r (echo power ∝ D²/r²); assumed, chosen so that moderate rain
  /// gives tens of spurious returns per sweep within 2 m.
  double detect_diameter_at_1m_mm = 2.5;
  double beam_area_m2 = 1.0e-4;  ///< near-field beam cross-section (about 1 cm², assumed)
  double near_min_m = 0.4;       ///< the emitter's minimum range (LidarSimConfig::min_range_m)
  double near_max_m = 4.0;       ///< drops beyond this never give a return
  /// Two-way power loss along the path, exp(−2·α·r), α (1/km) = 1.076·R^0.67 dB/km converted
  /// (the rain attenuation of 850–1550 nm free-space optical links, Carbonneau 1998 as used by
  /// ITU-R); it lowers the return probability of far and dark surfaces (DetectionConfig).
};

/// Dust raised by the robot's own wheels and the wind: intermittent clouds near the sensor,
/// low and behind or beside the wheels. A beam through a cloud is scattered back from inside
/// it, passes, or is lost (Phillips, Guenther & McAree, ACRA 2017, "When the dust settles: the
/// four behaviors of LiDAR in the presence of fine airborne particulates").
struct DustPuff {
  int64_t t_start_ns = 0;
  int64_t t_end_ns = 0;
  Eigen::Vector3d center_world = Eigen::Vector3d::Zero();  ///< at t_start
  Eigen::Vector3d wind_world_mps = Eigen::Vector3d::Zero();
  double radius_m = 1.0;
  double extinction_per_m = 1.0;  ///< scattering events per metre of path inside the cloud
  double loss_fraction = 0.3;     ///< of the beams that cross without a dust return, lost
};

struct DustConfig {
  bool on = false;
  std::vector<DustPuff> puffs;  ///< drawn from the seed by SetUpDust (disturb/weather_setup.h)
};

/// Return probability from the echo's power: a Lambertian surface of reflectivity ρ at range r
/// and incidence θ returns P ∝ ρ·cos θ / r², and the RS-LiDAR-16 detects a 20 % target at
/// 150 m (user manual: "measurement range 150 m"; the reflectivity the figure is for is
/// assumed); p = 1 / (1 + (P_ref/P)^k). Wet ground is darker (Lekner & Dorf, Applied Optics
/// 1988, 27(7) 1278, "Why some things are darker when wet") and puddles are mirrors that send a
/// grazing beam away.
struct DetectionConfig {
  bool on = false;
  double reference_reflectivity = 0.20;
  double reference_range_m = 150.0;
  double steepness = 4.0;          ///< k: 10 %–90 % detection over a factor 3 of power (assumed)
  double wet_ground_factor = 0.5;  ///< reflectivity of wet ground / dry (assumed)
  double puddle_cell_m = 1.5;      ///< puddles on a grid of this size
  double puddle_fraction = 0.08;   ///< of the ground's cells (assumed)
  /// A puddle's diffuse return left (of the wet ground's): still water reflects specularly,
  /// away from a sensor that sees it at grazing incidence (assumed).
  double puddle_reflectivity_factor = 0.001;
  uint64_t puddle_seed = 0;
};

struct LidarWeatherConfig {
  MixedPixelConfig mixed;
  RainConfig rain;
  DustConfig dust;
  DetectionConfig detection;
  bool Any() const { return mixed.on || rain.on || dust.on || detection.on; }
};

/// One firing as the emitter casts it.
struct WeatherRay {
  int64_t t_ns = 0;
  int laser = 0;
  Eigen::Vector3d origin_world = Eigen::Vector3d::Zero();  ///< lens centre
  Eigen::Vector3d dir_world = Eigen::Vector3d::UnitX();
  Eigen::Vector3d up_world = Eigen::Vector3d::UnitZ();  ///< the LiDAR's rotation axis
};

/// Counters over a run (for tests and the README's figures).
struct WeatherCounts {
  uint64_t rays = 0;
  uint64_t edge_checks = 0;  ///< rays whose footprint was probed with sub-rays
  uint64_t sub_rays = 0;     ///< extra rays cast for that
  uint64_t mixed = 0;        ///< returns moved between two surfaces
  uint64_t rain = 0;         ///< returns from drops
  uint64_t dust = 0;         ///< returns from dust
  uint64_t dust_lost = 0;
  uint64_t lost = 0;  ///< surface returns lost by the detection model
};

/// Airborne returns carry this reflectivity (0–255), as a LiDAR would report a weak echo.
constexpr float kAirborneReflectivity = 5.0f;

class LidarWeather {
 public:
  LidarWeather(const World* world, const LidarWeatherConfig& config, uint64_t seed);

  /// Changes the world's hit of one firing into what the sensor reports: the range moved for a
  /// mixed pixel, a drop or dust echo (cls kNone, range > 0), or no return (range < 0).
  void Apply(const WeatherRay& ray, double max_range_m, RayHit* hit);

  const WeatherCounts& counts() const { return counts_; }

 private:
  /// Where a footprint straddles two surfaces: the other surface and the edge's offset from
  /// the beam's centre (rad).
  struct FootprintEdge {
    bool found = false;
    RayHit other;
    double offset_rad = 0.0;
    int casts = 0;  ///< sub-rays cast to find it
  };

  void ApplyMixedPixel(const WeatherRay& ray, double max_range_m, RayHit* hit);
  FootprintEdge FindEdge(const WeatherRay& ray, double max_range_m, const RayHit& centre) const;
  bool ApplyRain(RayHit* hit);
  bool ApplyDust(const WeatherRay& ray, RayHit* hit);
  void ApplyDetection(const WeatherRay& ray, RayHit* hit);

  const World* world_;
  LidarWeatherConfig config_;
  Rng rng_;
  std::array<double, 16> previous_range_m_{};  ///< each laser's last hit (edge test)
  double rain_echo_probability_ = 0.0;         ///< per firing, 1 − exp(−RainEchoesPerRay)
  double rain_decay_per_m_ = 0.0;  ///< Λ·D1: drop echoes' density ∝ exp(−Λ·D1·r)
  double rain_alpha_per_m_ = 0.0;  ///< extinction: two-way transmission exp(−2αr)
  WeatherCounts counts_;
};

/// Mean number of drop echoes per firing for `rain` between its near_min_m and near_max_m.
double RainEchoesPerRay(const RainConfig& rain);

/// Rain's extinction coefficient α (1/m).
double RainExtinctionPerM(const RainConfig& rain);

/// Two-way rain transmission over `range_m`, exp(−2·α·r).
double RainTransmission(const RainConfig& rain, double range_m);

/// Detection probability of an echo of relative power `power` (ρ·cos θ·T²/r², ρ in 0–1).
double DetectionProbability(const DetectionConfig& d, double power);

/// Whether the ground at (x, y) is a puddle.
bool IsPuddle(const DetectionConfig& d, double x_m, double y_m);

}  // namespace swlio::sim
