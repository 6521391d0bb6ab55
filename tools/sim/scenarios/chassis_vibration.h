#pragma once
/// @file
/// Chassis vibration of the sensor head (the `vibration` disturbance, issue 36): a rigid motion
/// of the IMU and the LiDAR together, so that the IMU measures it and the LiDAR is cast from the
/// shaken pose. Two parts, each a sum of tones in 15–80 Hz:
/// - motors: three tones at fixed frequencies (a drive motor's fundamental, its second harmonic,
///   a gear mesh), present at all times: a standing robot's motors idle (holding torque, PWM,
///   fans, pumps);
/// - terrain: 16 tones spread over the band, their amplitude growing linearly with speed up to
///   1.5× the reference speed's (a wheel rolling over gravel excites a broadband spectrum that
///   grows with speed: Weiss, Fröhlich & Zell, IROS 2006, "Vibration-based terrain
///   classification using support vector machines"; DuPont et al., Autonomous Robots 24(4)
///   2008, "Frequency response method for terrain classification").
/// Magnitudes: the (no published RMS for a wheeled robot of this size on gravel was
/// found here): 0.5–1.0 m/s² RMS of acceleration at rest, 1.0–2.0 m/s² at 1 m/s, each drawn
/// per seed; the vertical axis carries 60 % of the power. Angular vibration: a rate RMS of
/// 0.02 rad/s per m/s² of acceleration RMS, mostly roll and pitch (assumed: a sprung chassis
/// rocking; 1 m/s² gives 0.02 rad/s, i.e. 0.01–0.03° amplitude at 15–80 Hz).

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace swlio::sim {

struct Kinematics;

struct ChassisVibrationSpec {
  double rest_rms_mps2 = 0.75;  ///< acceleration RMS (vector) standing, motors idling
  double drive_rms_mps2 = 1.5;  ///< at reference_speed_mps on gravel, motors and terrain
  double reference_speed_mps = 1.0;
  double max_terrain_gain = 1.5;       ///< terrain part at most this × its reference amplitude
  double rate_rms_per_acc_rms = 0.02;  ///< (rad/s) / (m/s²)
  double min_hz = 15.0;
  double max_hz = 80.0;
};

class ChassisVibration {
 public:
  /// Draws the tones (frequencies, axes, phases) from `seed`.
  ChassisVibration(const ChassisVibrationSpec& spec, uint64_t seed);

  /// Adds the vibration at time `t_s` to `k`, the kinematics without it: the IMU point moves by
  /// a small displacement (world axes) and the body turns by a small angle (body axes).
  void Apply(double t_s, Kinematics* k) const;

  const ChassisVibrationSpec& spec() const { return spec_; }
  /// The seed the tones were drawn from.
  uint64_t seed() const { return seed_; }
  /// Motor tone frequencies (Hz), for the manifest.
  std::vector<double> MotorFrequenciesHz() const;

 private:
  struct Tone {
    double omega_radps = 0.0;
    bool terrain = false;
    /// Acceleration (m/s²) and angular rate (rad/s) as c·cos ωt + s·sin ωt, per axis.
    Eigen::Vector3d acc_cos, acc_sin, rate_cos, rate_sin;
  };
  /// Terrain amplitude factor at `speed` and its rate of change.
  void TerrainGain(const Kinematics& k, double* gain, double* gain_rate) const;

  ChassisVibrationSpec spec_;
  uint64_t seed_ = 0;
  std::vector<Tone> tones_;
};

}  // namespace swlio::sim
