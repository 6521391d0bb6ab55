// WGS-84 geodetic ↔ ECEF ↔ local ENU (geodetic.h).

#include "swlio/core/geodetic.h"

#include <gtest/gtest.h>

namespace swlio {
namespace {

TEST(Geodetic, EcefOfKnownPoints) {
  // On the equator at the prime meridian the ECEF x is the semi-major axis; at the pole z is
  // the semi-minor axis b = a (1 − f) = 6356752.3142 m (NIMA TR8350.2, table 3.3).
  const Eigen::Vector3d e = GeodeticToEcef({0.0, 0.0, 0.0});
  EXPECT_NEAR(e.x(), 6378137.0, 1e-6);
  EXPECT_NEAR(e.y(), 0.0, 1e-6);
  const Eigen::Vector3d n = GeodeticToEcef({90.0, 0.0, 100.0});
  EXPECT_NEAR(n.z(), 6356752.3142 + 100.0, 1e-3);
}

TEST(Geodetic, RoundTripAnywhere) {
  for (double lat : {-89.0, -45.5, 0.0, 31.2, 60.0, 89.9}) {
    for (double lon : {-179.0, -60.0, 0.0, 121.47, 179.5}) {
      const Geodetic g{lat, lon, 123.4};
      const Geodetic back = EcefToGeodetic(GeodeticToEcef(g));
      EXPECT_NEAR(back.lat_deg, lat, 1e-10);
      EXPECT_NEAR(back.lon_deg, lon, 1e-10);
      EXPECT_NEAR(back.height_m, 123.4, 1e-5);
    }
  }
}

TEST(Geodetic, LocalEnuAxes) {
  const Geodetic origin{31.0, 121.0, 10.0};
  const LocalEnu enu(origin);
  EXPECT_LT(enu.ToEnu(origin).norm(), 1e-6);
  // 1e-4° of latitude north is ≈ 11.09 m at 31° (M = a(1−e²)/(1−e² sin²φ)^1.5 ≈ 6.3528e6 m).
  const Eigen::Vector3d north = enu.ToEnu({31.0001, 121.0, 10.0});
  EXPECT_NEAR(north.y(), 11.088, 0.01);
  EXPECT_NEAR(north.x(), 0.0, 1e-6);
  const Eigen::Vector3d east = enu.ToEnu({31.0, 121.0001, 10.0});
  EXPECT_GT(east.x(), 9.0);
  EXPECT_NEAR(east.y(), 0.0, 1e-3);
  const Eigen::Vector3d up = enu.ToEnu({31.0, 121.0, 15.0});
  EXPECT_NEAR(up.z(), 5.0, 1e-6);
  // Back from ENU.
  const Eigen::Vector3d p(120.0, -340.0, 2.5);
  EXPECT_LT((enu.ToEnu(enu.ToGeodetic(p)) - p).norm(), 1e-6);
}

}  // namespace
}  // namespace swlio
