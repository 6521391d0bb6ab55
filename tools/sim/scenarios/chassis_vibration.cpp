#include "scenarios/chassis_vibration.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rng.h"
#include "scenarios/trajectory.h"
#include "swlio/core/lie.h"

namespace swlio::sim {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kTerrainTones = 16;
/// Share of the acceleration power per axis (x forward, y left, z up) and of the angular rate's
/// (roll, pitch, yaw).
const Eigen::Vector3d kAccAxisPower(0.2, 0.2, 0.6);
const Eigen::Vector3d kRateAxisPower(0.45, 0.45, 0.1);
/// Motor tones' share of the motor part's power: fundamental, second harmonic, gear mesh.
constexpr double kMotorPower[3] = {0.6, 0.25, 0.15};

/// Per-axis c, s of a tone whose power (mean square) per axis is `power`: a random phase.
void RandomPhase(Rng& rng, const Eigen::Vector3d& power, Eigen::Vector3d* c, Eigen::Vector3d* s) {
  for (int i = 0; i < 3; ++i) {
    const double amplitude = std::sqrt(2.0 * power[i]);  // mean square of A·cos = A²/2
    const double phase = rng.Uniform(0.0, kTwoPi);
    (*c)[i] = amplitude * std::cos(phase);
    (*s)[i] = amplitude * std::sin(phase);
  }
}

}  // namespace

ChassisVibration::ChassisVibration(const ChassisVibrationSpec& spec, uint64_t seed)
    : spec_(spec), seed_(seed) {
  Rng rng(seed ^ 0x51B4A710ull);
  const double rest2 = spec.rest_rms_mps2 * spec.rest_rms_mps2;
  const double terrain2 = std::max(0.0, spec.drive_rms_mps2 * spec.drive_rms_mps2 - rest2);
  const double rate_per_acc2 = spec.rate_rms_per_acc_rms * spec.rate_rms_per_acc_rms;
  auto add = [&](double hz, bool terrain, double acc_power) {
    Tone t;
    t.omega_radps = kTwoPi * hz;
    t.terrain = terrain;
    RandomPhase(rng, acc_power * kAccAxisPower, &t.acc_cos, &t.acc_sin);
    RandomPhase(rng, acc_power * rate_per_acc2 * kRateAxisPower, &t.rate_cos, &t.rate_sin);
    tones_.push_back(t);
  };
  // Motors: a fundamental in the lower third of the band, its harmonic, a gear mesh near the top.
  const double f_motor = rng.Uniform(spec.min_hz + 5.0, spec.min_hz + 15.0);
  add(f_motor, false, kMotorPower[0] * rest2);
  add(2.0 * f_motor, false, kMotorPower[1] * rest2);
  add(rng.Uniform(spec.max_hz - 20.0, spec.max_hz - 5.0), false, kMotorPower[2] * rest2);
  const double step_hz = (spec.max_hz - spec.min_hz) / kTerrainTones;
  for (int i = 0; i < kTerrainTones; ++i) {
    const double hz = spec.min_hz + (i + rng.Uniform(0.1, 0.9)) * step_hz;
    add(hz, true, terrain2 / kTerrainTones);
  }
}

std::vector<double> ChassisVibration::MotorFrequenciesHz() const {
  std::vector<double> out;
  for (const Tone& t : tones_) {
    if (!t.terrain) out.push_back(t.omega_radps / kTwoPi);
  }
  return out;
}

void ChassisVibration::TerrainGain(const Kinematics& k, double* gain, double* gain_rate) const {
  // Speed smoothed near zero (|v| has no derivative there): sqrt(v² + v0²) − v0.
  constexpr double kV0 = 0.02;
  const double root = std::sqrt(k.v_world.squaredNorm() + kV0 * kV0);
  const double raw = (root - kV0) / spec_.reference_speed_mps;
  *gain = std::min(raw, spec_.max_terrain_gain);
  *gain_rate = raw >= spec_.max_terrain_gain
                   ? 0.0
                   : k.v_world.dot(k.a_world) / (root * spec_.reference_speed_mps);
}

void ChassisVibration::Apply(double t_s, Kinematics* k) const {
  double gain = 0.0, gain_rate = 0.0;
  TerrainGain(*k, &gain, &gain_rate);
  // Displacement d, its rate and acceleration; angle θ and its rate. For a tone
  // a(t) = c cos ωt + s sin ωt: d = −a/ω², d' = (−s cos ωt + c sin ωt)/ω... scaled by the gain
  // g(t): (g d)'' = g d'' + 2 g' d' (+ g'' d, below 1e-4 of the rest and left out).
  Eigen::Vector3d d = Eigen::Vector3d::Zero(), dv = d, da = d, theta = d, theta_rate = d;
  for (const Tone& tone : tones_) {
    const double w = tone.omega_radps;
    const double cw = std::cos(w * t_s), sw = std::sin(w * t_s);
    const double g = tone.terrain ? gain : 1.0;
    const double g_rate = tone.terrain ? gain_rate : 0.0;
    const Eigen::Vector3d acc = tone.acc_cos * cw + tone.acc_sin * sw;
    const Eigen::Vector3d vel = (tone.acc_cos * sw - tone.acc_sin * cw) / w;  // ∫acc
    const Eigen::Vector3d pos = -acc / (w * w);                               // ∫∫acc
    const Eigen::Vector3d rate = tone.rate_cos * cw + tone.rate_sin * sw;
    const Eigen::Vector3d angle = (tone.rate_cos * sw - tone.rate_sin * cw) / w;
    d += g * pos;
    dv += g * vel + g_rate * pos;
    da += g * acc + 2.0 * g_rate * vel;
    theta += g * angle;
    theta_rate += g * rate + g_rate * angle;
  }
  const Eigen::Matrix3d R_vib = lie::Exp(theta);
  k->p_world += d;
  k->v_world += dv;
  k->a_world += da;
  k->omega_body = R_vib.transpose() * k->omega_body + lie::RightJacobian(theta) * theta_rate;
  k->R_world_body = k->R_world_body * R_vib;
}

}  // namespace swlio::sim
