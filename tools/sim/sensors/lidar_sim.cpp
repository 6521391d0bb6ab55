#include "sensors/lidar_sim.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "swlio/core/lie.h"
#include "swlio/core/time.h"
#include "swlio/drivers/rs16_encoder.h"

namespace swlio::sim {
namespace {

using drivers::rs16::kFiringPeriodNs;
using drivers::rs16::kLaserSpacingNs;
constexpr int kFiringsPerPacket = 2 * drivers::rs16::kBlocks;
constexpr double kDegToRad = std::numbers::pi / 180.0;
/// KeyedDraws seed offset of the packets' receive jitter (rays are keyed on the noise seed itself).
constexpr uint64_t kPacketStream = 0x7A1E5ull;

double PacketStartS(uint64_t index) { return NsToSec(static_cast<int64_t>(index) * kMsopPeriodNs); }

}  // namespace

double SimAzimuthDeg(const LidarSimConfig& config, double t_s) {
  const double a = config.initial_azimuth_deg + 360.0 * config.rpm / 60.0 * t_s;
  return a - 360.0 * std::floor(a / 360.0);
}

Eigen::Vector3d SimRayDirection(const LidarSimConfig& config, size_t channel, double azimuth_rad) {
  const double omega = config.vertical_angles_deg[channel] * kDegToRad;
  return {std::cos(omega) * std::cos(azimuth_rad), -std::cos(omega) * std::sin(azimuth_rad),
          std::sin(omega)};
}

Eigen::Vector3d SimLensCentre(const LidarSimConfig& config, double azimuth_rad) {
  return config.lens_offset_m * Eigen::Vector3d(std::cos(azimuth_rad), -std::sin(azimuth_rad), 0.0);
}

Eigen::Vector3d SimDecodedPoint(const LidarSimConfig& config,
                                size_t channel,
                                int64_t t_ns,
                                double range_m) {
  const double alpha = SimAzimuthDeg(config, NsToSec(t_ns)) * kDegToRad;
  return SimLensCentre(config, alpha) + range_m * SimRayDirection(config, channel, alpha);
}

LidarSimulator::LidarSimulator(const World* world,
                               const Trajectory* trajectory,
                               const LidarSimConfig& config,
                               uint64_t seed)
    : world_(world), trajectory_(trajectory), config_(config), noise_seed_(seed ^ 0x11DA4ull) {
  if (config_.weather.Any()) {
    weather_.emplace(world_, config_.weather, seed);
  }
}

Eigen::Isometry3d LidarSimulator::LidarPose(double t_s) const {
  const Kinematics k = trajectory_->At(t_s);
  Eigen::Isometry3d T_world_imu = Eigen::Isometry3d::Identity();
  T_world_imu.linear() = k.R_world_body;
  T_world_imu.translation() = k.p_world;
  return T_world_imu * config_.T_imu_lidar;
}

int64_t LidarSimulator::MsopRxNs(uint64_t index) const {
  const int64_t last_firing_ns = (kFiringsPerPacket - 1) * kFiringPeriodNs + 15 * kLaserSpacingNs;
  return SecToNs(PacketStartS(index)) + last_firing_ns + SecToNs(config_.latency_s);
}

void LidarSimulator::SkipTo(double t_s) {
  const double period_s = NsToSec(kMsopPeriodNs);
  msop_index_ = std::max(msop_index_, static_cast<uint64_t>(std::ceil(t_s / period_s)));
  difop_index_ = std::max(difop_index_, static_cast<uint64_t>(std::ceil(t_s)));
}

bool LidarSimulator::Next(SimPacket* out, std::vector<SimReturn>* returns) {
  const double t_msop = PacketStartS(msop_index_);
  if (t_msop > trajectory_->duration_s()) return false;
  const double t_difop = static_cast<double>(difop_index_);  // one DIFOP per second
  if (t_difop <= t_msop) {
    if (returns != nullptr) returns->clear();  // a DIFOP carries no returns
    MakeDifop(out);
    return true;
  }
  MakeMsop(out, returns);
  return true;
}

void LidarSimulator::MakeDifop(SimPacket* out) {
  const double t_s = static_cast<double>(difop_index_++);
  drivers::Rs16DifopContent c;
  c.rpm = static_cast<uint16_t>(std::lround(config_.rpm));
  c.msop_port = config_.msop_port;
  c.difop_port = config_.difop_port;
  c.vertical_angles_deg = config_.vertical_angles_deg;
  c.t_sensor_ns = SecToNs(config_.clock.ToDevice(t_s));
  drivers::EncodeRs16Difop(c, out->bytes);
  out->t_header_s = t_s;
  out->dst_port = config_.difop_port;
  out->t_rx_ns = std::max(SecToNs(t_s + config_.latency_s), last_rx_ns_ + 1000);
  last_rx_ns_ = out->t_rx_ns;
}

double LidarSimulator::ActorTimeS(double t_s) const {
  const double lap_s = trajectory_->lap_period_s();
  return lap_s > 0.0 ? std::fmod(t_s, lap_s) : t_s;
}

void LidarSimulator::BeginActors(double t0_s, const Eigen::Isometry3d& pose) {
  const double t1_s = t0_s + NsToSec(kMsopPeriodNs);
  auto horizontal = [&](double t_s) {
    const double alpha = SimAzimuthDeg(config_, t_s) * kDegToRad;
    return Eigen::Vector2d((pose.linear() * SimRayDirection(config_, 0, alpha)).head<2>())
        .normalized();
  };
  actor_rays_.BeginPacket(*world_->actors, ActorTimeS(t0_s), ActorTimeS(t0_s) + (t1_s - t0_s),
                          pose.translation(), horizontal(t0_s), horizontal(t1_s),
                          config_.max_range_m);
}

void LidarSimulator::MakeMsop(SimPacket* out, std::vector<SimReturn>* returns) {
  const uint64_t index = msop_index_++;
  const double t0 = PacketStartS(index);
  drivers::Rs16MsopContent content;
  content.t_sensor_ns = SecToNs(config_.clock.ToDevice(t0));
  out->t_header_s = t0;
  if (returns != nullptr) returns->clear();
  Eigen::Isometry3d pose_a = LidarPose(t0);
  const bool actors = world_->actors != nullptr;
  if (actors) BeginActors(t0, pose_a);
  for (int f = 0; f < kFiringsPerPacket; ++f) {
    const double t_seq = t0 + NsToSec(f * kFiringPeriodNs);
    if (actors) actor_rays_.SetTime(ActorTimeS(t_seq));
    const Eigen::Isometry3d pose_b = LidarPose(t_seq + NsToSec(kFiringPeriodNs));
    const Eigen::Vector3d dphi = lie::Log(pose_a.linear().transpose() * pose_b.linear());
    auto& block = content.blocks[static_cast<size_t>(f / 2)];
    if (f % 2 == 0) block.azimuth_deg = SimAzimuthDeg(config_, t_seq);
    for (int laser = 0; laser < 16; ++laser) {
      // Pose at this laser's own time, interpolated inside the 55.5 µs firing sequence.
      const double frac = static_cast<double>(laser * kLaserSpacingNs) / kFiringPeriodNs;
      const double t_fire = t_seq + NsToSec(laser * kLaserSpacingNs);
      const Eigen::Vector3d origin =
          (1.0 - frac) * pose_a.translation() + frac * pose_b.translation();
      const Eigen::Matrix3d R = pose_a.linear() * lie::Exp(frac * dphi);
      const double alpha = SimAzimuthDeg(config_, t_fire) * kDegToRad;
      const Eigen::Vector3d dir = R * SimRayDirection(config_, static_cast<size_t>(laser), alpha);
      const Eigen::Vector3d lens = origin + R * SimLensCentre(config_, alpha);
      RayHit hit = world_->Cast(lens, dir, config_.max_range_m);
      uint16_t actor = 0;
      bool moving = false;
      if (actors) actor_rays_.Cast(lens, dir, config_.max_range_m, &hit, &actor, &moving);
      if (weather_) {
        weather_->Apply({SecToNs(t_fire), laser, lens, dir, R.col(2)}, config_.max_range_m, &hit);
        // Rain and dust returns (class none) come from no actor.
        if (hit.cls == SurfaceClass::kNone) {
          actor = 0;
          moving = false;
        }
      }
      // Every ray draws the same three numbers whatever it hit (KeyedDraws).
      KeyedDraws draws(noise_seed_, (index * kFiringsPerPacket + f) * 16 + laser);
      const double u_dropout = draws.Uniform();
      const double range_noise_m = draws.Normal(config_.range_sigma_m);
      const double u_intensity = draws.Uniform();
      double range = 0.0;
      if (hit.range_m > 0.0 && u_dropout >= config_.dropout) {
        range = hit.range_m + range_noise_m;
        if (range < config_.min_range_m || range > config_.max_range_m) range = 0.0;
      }
      const size_t slot = 16 * static_cast<size_t>(f % 2) + static_cast<size_t>(laser);
      block.range_m[slot] = static_cast<float>(range);
      block.intensity[slot] = static_cast<uint8_t>(
          std::clamp(hit.reflectivity * (0.9 + 0.2 * u_intensity), 0.0, 255.0));
      if (returns != nullptr) {
        returns->push_back({SecToNs(t_fire), static_cast<uint8_t>(f / 2),
                            static_cast<uint8_t>(slot), static_cast<uint8_t>(laser), range,
                            hit.range_m, hit.cls, lens + std::max(hit.range_m, 0.0) * dir, actor,
                            moving});
      }
    }
    pose_a = pose_b;
  }
  drivers::EncodeRs16Msop(content, out->bytes);
  out->dst_port = config_.msop_port;
  const double u_jitter = KeyedDraws(noise_seed_ ^ kPacketStream, index).Uniform();
  out->t_rx_ns =
      std::max(MsopRxNs(index) + SecToNs(u_jitter * config_.latency_jitter_s), last_rx_ns_ + 1000);
  last_rx_ns_ = out->t_rx_ns;
}

}  // namespace swlio::sim
