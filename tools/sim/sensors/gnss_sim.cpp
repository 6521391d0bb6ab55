// GnssPvtData of the simulated MTi-G-710. Field units (u-blox M8 receiver description,
// UBX-NAV-PVT, which the MTi's GnssPvtData copies; MT0101P "Contents of GnssPvtData"):
// iTOW ms of the GPS week; lon/lat 1e-7 deg; height (above the ellipsoid) and hMSL in mm;
// hAcc/vAcc mm; velN/E/D and gSpeed mm/s; headMot 1e-5 deg; sAcc mm/s; headAcc 1e-5 deg;
// DOPs 0.01. valid bits: 0 validDate, 1 validTime, 2 fullyResolved. flags bits: 0 gnssFixOK,
// 1 diffSoln. fixType: 0 no fix, 2 2D, 3 3D.

#include "sensors/gnss_sim.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rng.h"
#include "swlio/core/time.h"

namespace swlio::sim {
namespace {

namespace xs = drivers::xsens;

constexpr int64_t kGpsEpochUnixS = 315'964'800;  // 1980-01-06T00:00:00Z
constexpr int64_t kGpsMinusUtcS = 18;            // leap seconds since 2017-01-01
constexpr int64_t kWeekS = 604'800;
constexpr uint32_t kNoFixAccuracyMm = 100'000'000;  // 100 km: what a receiver without a fix says

/// A first-order Gauss–Markov process per ENU axis (formula in gnss_sim.h).
class GaussMarkov3 {
 public:
  GaussMarkov3(const GnssErrorModel& m, Rng* rng)
      : sigma_(m.sigma_h_m, m.sigma_h_m, m.sigma_v_m), tau_s_(m.correlation_time_s), rng_(rng) {}

  Eigen::Vector3d Step(double dt_s) {
    const double phi = started_ && tau_s_ > 0.0 ? std::exp(-dt_s / tau_s_) : 0.0;
    const double drive = std::sqrt(1.0 - phi * phi);
    for (int a = 0; a < 3; ++a) e_(a) = phi * e_(a) + drive * rng_->Normal(sigma_(a));
    started_ = true;
    return e_;
  }

 private:
  Eigen::Vector3d sigma_;
  double tau_s_;
  Rng* rng_;
  Eigen::Vector3d e_ = Eigen::Vector3d::Zero();
  bool started_ = false;
};

/// Civil date from days since 1970-01-01 (H. Hinnant, "chrono-Compatible Low-Level Date
/// Algorithms", civil_from_days).
void CivilFromDays(int64_t z, int64_t* y, unsigned* m, unsigned* d) {
  z += 719468;
  const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const auto doe = static_cast<unsigned>(z - era * 146097);
  const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const unsigned mp = (5 * doy + 2) / 153;
  *d = doy - (153 * mp + 2) / 5 + 1;
  *m = mp < 10 ? mp + 3 : mp - 9;
  *y = static_cast<int64_t>(yoe) + era * 400 + (*m <= 2 ? 1 : 0);
}

/// Time fields of the fix at UTC `unix_ns`.
void SetTime(int64_t unix_ns, xs::XsensGnssPvt* p) {
  const int64_t s = unix_ns / kNsPerSec;
  const int64_t ns = unix_ns % kNsPerSec;
  int64_t year = 0;
  unsigned month = 0, day = 0;
  CivilFromDays(s / 86'400, &year, &month, &day);
  const int64_t sod = s % 86'400;
  p->year = static_cast<uint16_t>(year);
  p->month = static_cast<uint8_t>(month);
  p->day = static_cast<uint8_t>(day);
  p->hour = static_cast<uint8_t>(sod / 3600);
  p->min = static_cast<uint8_t>(sod / 60 % 60);
  p->sec = static_cast<uint8_t>(sod % 60);
  p->nano_ns = static_cast<int32_t>(ns);
  p->valid = 0x07;  // validDate | validTime | fullyResolved
  p->t_acc_ns = 20;
  const int64_t gps_s = s - kGpsEpochUnixS + kGpsMinusUtcS;
  p->itow_ms = static_cast<uint32_t>((gps_s % kWeekS) * 1000 + ns / 1'000'000);
}

int32_t ToI32(double v) {
  return static_cast<int32_t>(std::clamp(std::nearbyint(v), -2147483648.0, 2147483647.0));
}

uint32_t ToU32(double v) { return static_cast<uint32_t>(std::clamp(std::nearbyint(v), 0.0, 4e9)); }

/// Position, accuracies and quality of a 3-D SBAS fix.
void SetPosition(const Geodetic& g, const GnssSimConfig& c, xs::XsensGnssPvt* p) {
  const GnssErrorModel& n = c.noise;
  p->fix_type = 3;
  p->flags = 0x03;  // gnssFixOK | diffSoln (SBAS)
  p->num_sv = c.num_sv;
  p->lat_1e7deg = ToI32(g.lat_deg * 1e7);
  p->lon_1e7deg = ToI32(g.lon_deg * 1e7);
  p->height_mm = ToI32(g.height_m * 1e3);
  p->hmsl_mm = p->height_mm;  // no geoid model: geoid separation taken as 0
  p->h_acc_mm = ToU32(n.accuracy_inflation * std::numbers::sqrt2 * n.sigma_h_m * 1e3);
  p->v_acc_mm = ToU32(n.accuracy_inflation * n.sigma_v_m * 1e3);
  p->gdop = 180;  // plausible open-sky values (0.01 units)
  p->pdop = 150;
  p->tdop = 90;
  p->vdop = 120;
  p->hdop = 90;
  p->ndop = 60;
  p->edop = 70;
}

/// Velocity (NED, mm/s), ground speed, heading of motion and their accuracies.
void SetVelocity(const Eigen::Vector3d& v_enu_mps, const GnssErrorModel& n, xs::XsensGnssPvt* p) {
  const double v_n = v_enu_mps.y(), v_e = v_enu_mps.x();
  p->vel_n_mmps = ToI32(v_n * 1e3);
  p->vel_e_mmps = ToI32(v_e * 1e3);
  p->vel_d_mmps = ToI32(-v_enu_mps.z() * 1e3);
  const double speed = std::hypot(v_n, v_e);
  p->g_speed_mmps = ToI32(speed * 1e3);
  double head_deg = std::atan2(v_e, v_n) * 180.0 / std::numbers::pi;
  if (head_deg < 0.0) head_deg += 360.0;
  p->head_mot_1e5deg = ToI32(head_deg * 1e5);
  const double s_acc = n.accuracy_inflation * std::sqrt(3.0) * n.velocity_sigma_mps;
  p->s_acc_mmps = ToU32(s_acc * 1e3);
  const double head_acc_deg =
      speed > s_acc ? std::asin(std::min(1.0, s_acc / speed)) * 180.0 / std::numbers::pi : 180.0;
  p->head_acc_1e5deg = ToU32(head_acc_deg * 1e5);
}

/// During an outage: no fix, the last position held, accuracies of a receiver that has none.
void MarkNoFix(xs::XsensGnssPvt* p) {
  p->fix_type = 0;
  p->flags = 0;
  p->num_sv = 2;
  p->h_acc_mm = kNoFixAccuracyMm;
  p->v_acc_mm = kNoFixAccuracyMm;
  p->vel_n_mmps = p->vel_e_mmps = p->vel_d_mmps = p->g_speed_mmps = 0;
  p->pdop = p->gdop = p->hdop = p->vdop = 9999;
}

bool InOutage(const GnssSimConfig& c, double t_s) {
  return std::any_of(c.outages.begin(), c.outages.end(),
                     [t_s](const TimeWindow& w) { return w.Contains(t_s); });
}

double JumpEast(const GnssSimConfig& c, double t_s) {
  double east = 0.0;
  for (const GnssJump& j : c.jumps) east += j.Contains(t_s) ? j.east_m : 0.0;
  return east;
}

}  // namespace

Eigen::Vector3d TrueAntennaEnu(const Kinematics& imu, const Eigen::Vector3d& p_imu_antenna_m) {
  return imu.p_world + imu.R_world_body * p_imu_antenna_m;
}

std::vector<SimGnssFix> SimulateGnss(const Trajectory& trajectory,
                                     const GnssSimConfig& config,
                                     const std::vector<SimImuSample>& imu,
                                     uint64_t seed) {
  Rng rng(seed ^ 0x6E55F1ull);
  GaussMarkov3 error(config.noise, &rng);
  const LocalEnu enu(config.origin);
  std::vector<SimGnssFix> out;
  xs::XsensGnssPvt held;  // the last position reported with a fix
  double last_t_s = 0.0;
  for (size_t i = 0; i < imu.size(); ++i) {
    if (!imu[i].has_gnss_pvt) continue;
    const double t_s = NsToSec(imu[i].t_true_ns);
    const Kinematics k = trajectory.At(t_s);
    SimGnssFix f;
    f.imu_index = i;
    f.t_true_ns = imu[i].t_true_ns;
    f.p_enu_true_m = TrueAntennaEnu(k, config.p_imu_antenna_m);
    f.error_enu_m = error.Step(t_s - last_t_s) + Eigen::Vector3d(JumpEast(config, t_s), 0, 0);
    last_t_s = t_s;
    const Eigen::Vector3d v_antenna =
        k.v_world + k.R_world_body * k.omega_body.cross(config.p_imu_antenna_m);
    const double sv = config.noise.velocity_sigma_mps;
    const Eigen::Vector3d v_noise(rng.Normal(sv), rng.Normal(sv), rng.Normal(sv));
    f.has_fix = !InOutage(config, t_s);
    if (f.has_fix) {
      SetPosition(enu.ToGeodetic(f.p_enu_true_m + f.error_enu_m), config, &f.pvt);
      SetVelocity(v_antenna + v_noise, config.noise, &f.pvt);
      held = f.pvt;
    } else {
      f.pvt = held;
      MarkNoFix(&f.pvt);
    }
    SetTime(config.utc_start_unix_s * kNsPerSec + f.t_true_ns, &f.pvt);
    out.push_back(f);
  }
  return out;
}

}  // namespace swlio::sim
