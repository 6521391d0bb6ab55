#pragma once
/// @file
/// RS-LiDAR-16 emitter: casts every laser firing from the pose at its own time (per-firing
/// timing of the real unit: 16 lasers 2.8 µs apart, a firing sequence every 55.5 µs, two per
/// block, 12 blocks per MSOP packet) and writes real MSOP and DIFOP bytes with the drivers'
/// encoder. Geometry is the decoder's (rs16_decoder.h: rs_driver's frame, x forward at azimuth
/// 0, y left, z up): each ray starts at the lens centre, `lens_offset_m` out along the firing
/// azimuth, so that a decoded return is the cast point again (to the wire's quantization).

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "rng.h"
#include "scenarios/trajectory.h"
#include "sensors/imu_sim.h"
#include "sensors/lidar_weather.h"
#include "swlio/drivers/rs16_protocol.h"
#include "world/actor_rays.h"
#include "world/world.h"

namespace swlio::sim {

struct LidarSimConfig {
  double rpm = 600.0;
  /// By laser channel as transmitted (RS16: channels 0–7 down, 8–15 up); sent in DIFOP.
  std::array<double, 16> vertical_angles_deg = {-15, -13, -11, -9, -7, -5, -3, -1,
                                                15,  13,  11,  9,  7,  5,  3,  1};
  double range_sigma_m = 0.02;  ///< RS16 datasheet accuracy ±2 cm (typical)
  double min_range_m = 0.4;
  double max_range_m = 150.0;
  double dropout = 0.002;  ///< probability that a valid hit still gives no return
  Eigen::Isometry3d T_imu_lidar = Eigen::Isometry3d::Identity();
  DeviceClock clock;          ///< header time = clock.ToDevice(host time)
  double latency_s = 0.0003;  ///< last firing of a packet → host receive
  double latency_jitter_s = 0.0001;
  double initial_azimuth_deg = 0.0;  ///< motor angle at host time 0
  /// Lens centre's distance from the rotation axis: the decoder's default (rs_driver's RX).
  double lens_offset_m = drivers::rs16::kLensRxM;
  uint16_t msop_port = 6699;
  uint16_t difop_port = 7788;
  /// Mixed pixels, rain, dust and dropouts (sensors/lidar_weather.h); all off by default.
  LidarWeatherConfig weather;
};

/// One MSOP packet's period: 12 blocks of two firing sequences (1.332 ms).
constexpr int64_t kMsopPeriodNs =
    int64_t{2} * drivers::rs16::kBlocks * drivers::rs16::kFiringPeriodNs;

struct SimPacket {
  int64_t t_rx_ns = 0;  ///< host receive time
  /// Simulation time that the header's sensor time stands for (an MSOP's first firing, a
  /// DIFOP's whole second), before the sensor clock's offset and drift.
  double t_header_s = 0.0;
  uint16_t dst_port = 0;
  std::array<uint8_t, drivers::rs16::kPacketBytes> bytes{};
};

/// Ground truth of one simulated return, for tests.
struct SimReturn {
  int64_t t_true_ns = 0;      ///< host time of the firing
  uint8_t block = 0;          ///< block index in its packet
  uint8_t slot = 0;           ///< slot in its block (0–31)
  uint8_t channel = 0;        ///< laser channel as transmitted
  double range_m = 0.0;       ///< noisy range written to the packet (0 = no return)
  double true_range_m = 0.0;  ///< from the lens centre to the surface
  SurfaceClass cls = SurfaceClass::kNone;
  Eigen::Vector3d p_world = Eigen::Vector3d::Zero();  ///< true hit point
  uint16_t actor = 0;   ///< 0: the static world; else the id of the actor hit (world/actors.h)
  bool moving = false;  ///< that actor moves at some time during the drive (ActorSet::Moving)
};

/// Motor azimuth at simulation time `t_s`, degrees in [0, 360), clockwise seen from above.
double SimAzimuthDeg(const LidarSimConfig& config, double t_s);

/// Unit ray of laser `channel` at azimuth `azimuth_rad`, LiDAR frame:
/// (cos ω cos α, −cos ω sin α, sin ω).
Eigen::Vector3d SimRayDirection(const LidarSimConfig& config, size_t channel, double azimuth_rad);

/// The lens centre at azimuth `azimuth_rad`, LiDAR frame: L·(cos α, −sin α, 0).
Eigen::Vector3d SimLensCentre(const LidarSimConfig& config, double azimuth_rad);

/// Where the decoder puts a return of `range_m` fired by `channel` at host time `t_ns`, in the
/// LiDAR frame at that firing: the lens centre plus the range along the ray.
Eigen::Vector3d SimDecodedPoint(const LidarSimConfig& config,
                                size_t channel,
                                int64_t t_ns,
                                double range_m);

class LidarSimulator {
 public:
  LidarSimulator(const World* world,
                 const Trajectory* trajectory,
                 const LidarSimConfig& config,
                 uint64_t seed);

  /// The next packet in receive order (DIFOP once a second, MSOP otherwise); false at the end
  /// of the trajectory. When `returns` is given it receives the truth of the MSOP's 384 slots
  /// (emptied for a DIFOP).
  bool Next(SimPacket* out, std::vector<SimReturn>* returns = nullptr);

  /// Continues from sim time `t_s` without casting the packets before it (for tests that need
  /// one sweep late in a drive; each ray's noise is a full run's, KeyedDraws).
  void SkipTo(double t_s);

  uint64_t msop_packets() const { return msop_index_; }
  uint64_t difop_packets() const { return difop_index_; }
  /// The weather model's counters; nothing when no weather model is on.
  const LidarWeather* weather() const { return weather_ ? &*weather_ : nullptr; }

 private:
  void MakeMsop(SimPacket* out, std::vector<SimReturn>* returns);
  void MakeDifop(SimPacket* out);
  /// The actors' time at simulation time `t_s`: they repeat every lap of a repeated route
  /// (RepeatRoute), as LidarLaps replays the first lap's packets.
  double ActorTimeS(double t_s) const;
  /// Picks the actors this packet (starting at simulation time `t0_s`, LiDAR pose `pose`) may
  /// hit, at their time (ActorTimeS).
  void BeginActors(double t0_s, const Eigen::Isometry3d& pose);
  Eigen::Isometry3d LidarPose(double t_s) const;
  int64_t MsopRxNs(uint64_t index) const;

  const World* world_;
  const Trajectory* trajectory_;
  LidarSimConfig config_;
  uint64_t noise_seed_;   ///< KeyedDraws per ray (range, dropout, intensity) and per packet
  ActorRays actor_rays_;  ///< the actors a packet's rays may hit (world_->actors)
  uint64_t msop_index_ = 0;
  uint64_t difop_index_ = 0;
  int64_t last_rx_ns_ = 0;               ///< keeps receive times in order
  std::optional<LidarWeather> weather_;  ///< only when a weather model is on
};

}  // namespace swlio::sim
