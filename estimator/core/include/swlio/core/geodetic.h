#pragma once
/// @file
/// WGS-84 geodetic coordinates, ECEF, and a local east-north-up (ENU) tangent frame.
///
/// Constants: WGS-84 semi-major axis a = 6378137 m, flattening f = 1/298.257223563 (NIMA
/// TR8350.2, table 3.1); e² = f(2 − f). Heights are ellipsoidal (what u-blox NAV-PVT calls
/// `height`, and the MTi's GnssPvtData carries).
///   geodetic → ECEF: N = a / √(1 − e² sin²φ);  X = (N + h) cosφ cosλ,  Y = (N + h) cosφ sinλ,
///                    Z = (N(1 − e²) + h) sinφ
///   ECEF → geodetic: fixed-point iteration on φ (converges to < 1e-12 rad in a few steps
///                    anywhere near the Earth's surface)
///   ECEF → ENU at origin (φ0, λ0): rows  e = [−sinλ0, cosλ0, 0],
///                    n = [−sinφ0 cosλ0, −sinφ0 sinλ0, cosφ0],  u = [cosφ0 cosλ0, cosφ0 sinλ0,
///                    sinφ0]
/// Header-only (the simulator uses it to make fixes, the estimator to read them).

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace swlio {

struct Geodetic {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double height_m = 0.0;  ///< above the WGS-84 ellipsoid
};

namespace wgs84 {
inline constexpr double kA = 6378137.0;
inline constexpr double kF = 1.0 / 298.257223563;
inline constexpr double kE2 = kF * (2.0 - kF);
}  // namespace wgs84

inline Eigen::Vector3d GeodeticToEcef(const Geodetic& g) {
  const double lat = g.lat_deg * std::numbers::pi / 180.0;
  const double lon = g.lon_deg * std::numbers::pi / 180.0;
  const double s = std::sin(lat);
  const double n = wgs84::kA / std::sqrt(1.0 - wgs84::kE2 * s * s);
  return {(n + g.height_m) * std::cos(lat) * std::cos(lon),
          (n + g.height_m) * std::cos(lat) * std::sin(lon),
          (n * (1.0 - wgs84::kE2) + g.height_m) * s};
}

inline Geodetic EcefToGeodetic(const Eigen::Vector3d& ecef) {
  const double p = std::hypot(ecef.x(), ecef.y());
  double lat = std::atan2(ecef.z(), p * (1.0 - wgs84::kE2));
  double h = 0.0;
  for (int i = 0; i < 10; ++i) {
    const double s = std::sin(lat);
    const double n = wgs84::kA / std::sqrt(1.0 - wgs84::kE2 * s * s);
    h = std::abs(std::cos(lat)) > 1e-9 ? p / std::cos(lat) - n : std::abs(ecef.z()) - n;
    const double next = std::atan2(ecef.z(), p * (1.0 - wgs84::kE2 * n / (n + h)));
    const bool done = std::abs(next - lat) < 1e-14;
    lat = next;
    if (done) break;
  }
  return {lat * 180.0 / std::numbers::pi, std::atan2(ecef.y(), ecef.x()) * 180.0 / std::numbers::pi,
          h};
}

/// The tangent frame at `origin`: x east, y north, z up (metres).
class LocalEnu {
 public:
  explicit LocalEnu(const Geodetic& origin) : origin_ecef_(GeodeticToEcef(origin)) {
    const double lat = origin.lat_deg * std::numbers::pi / 180.0;
    const double lon = origin.lon_deg * std::numbers::pi / 180.0;
    const double sf = std::sin(lat), cf = std::cos(lat), sl = std::sin(lon), cl = std::cos(lon);
    R_enu_ecef_ << -sl, cl, 0.0, -sf * cl, -sf * sl, cf, cf * cl, cf * sl, sf;
  }
  Eigen::Vector3d ToEnu(const Geodetic& g) const {
    return R_enu_ecef_ * (GeodeticToEcef(g) - origin_ecef_);
  }
  Geodetic ToGeodetic(const Eigen::Vector3d& enu_m) const {
    return EcefToGeodetic(origin_ecef_ + R_enu_ecef_.transpose() * enu_m);
  }

 private:
  Eigen::Vector3d origin_ecef_;
  Eigen::Matrix3d R_enu_ecef_;
};

}  // namespace swlio
