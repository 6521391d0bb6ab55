#include "scenarios/scenarios.h"

#include <numbers>

#include "rng.h"

#include "world/substation.h"

namespace swlio::sim {
namespace {

using L = Layout;

RouteSpec Base(double cruise_mps, double radius_m, const std::vector<Eigen::Vector2d>& points) {
  RouteSpec r;
  r.cruise_speed_mps = cruise_mps;
  for (const auto& p : points) r.waypoints.push_back({p, radius_m});
  return r;
}

Scenario Short() {
  Scenario s{
      "short", "about 60 s: along the south road, a left turn onto the east road", {}, {}, {}};
  s.route =
      Base(1.2, 4.0, {{150.0, L::kRoadSouth}, {L::kRoadEast, L::kRoadSouth}, {L::kRoadEast, 35.0}});
  return s;
}

Scenario Loop943() {
  Scenario s{"loop943",
             "a 943 m patrol: ring and middle roads, then a loop through the open yard, back to "
             "the start; revisits the east and south roads",
             {},
             {},
             {}};
  s.route = Base(1.0, 4.0,
                 {{60.0, L::kRoadSouth},
                  {L::kRoadEast, L::kRoadSouth},
                  {L::kRoadEast, L::kRoadMiddle},
                  {L::kRoadWest, L::kRoadMiddle},
                  {L::kRoadWest, L::kRoadNorth},
                  {L::kRoadEast, L::kRoadNorth},
                  {L::kRoadEast, L::kRoadSouth},
                  {L::kRoadWest, L::kRoadSouth},
                  {20.0, L::kRoadSouth},
                  {20.0, 63.5},
                  {L::kRoadWest, 63.5},
                  {L::kRoadWest, L::kRoadSouth},
                  {60.0, L::kRoadSouth}});
  return s;
}

Scenario Degenerate() {
  Scenario s{"degenerate",
             "a long stretch across the open yard, then along the west and south fences",
             {},
             {},
             {}};
  s.route = Base(1.2, 4.0, {{20.0, 0.0}, {20.0, 85.0}, {-7.0, 85.0}, {-7.0, -3.0}, {35.0, -3.0}});
  return s;
}

Scenario Aggressive() {
  Scenario s{"aggressive",
             "fast (1.5 m/s) slalom with yaw rates near 60 °/s, over road bumps, sharp corners",
             {},
             {},
             {}};
  std::vector<Eigen::Vector2d> pts = {{60.0, L::kRoadSouth}};
  for (int i = 1; i <= 8; ++i) {  // slalom across the south road, over the bump at x = 120
    pts.emplace_back(60.0 + 9.0 * i, L::kRoadSouth + (i % 2 == 1 ? 2.5 : -2.5));
  }
  pts.emplace_back(150.0, L::kRoadSouth);
  pts.emplace_back(L::kRoadEast, L::kRoadSouth);
  pts.emplace_back(L::kRoadEast, L::kRoadMiddle);  // over the bump at y = 40
  pts.emplace_back(90.0, L::kRoadMiddle);          // over the bump at x = 100
  s.route = Base(1.5, 1.5, pts);
  s.route.max_yaw_rate_radps = 60.0 * std::numbers::pi / 180.0 * 1.05;
  s.route.max_lateral_acc_mps2 = 2.0;
  s.route.mean_acc_mps2 = 0.6;
  return s;
}

/// `aggressive`'s slalom and corners over a calibration course: cable covers laid at ±45°
/// across the south road, at the slalom's first five turns and the centre-line crossings after
/// them, so that each one tips the robot about both horizontal axes. A drive that only yaws
/// leaves the vertical lever arm of the IMU-LiDAR extrinsic unobservable
/// (docs/notes/2026-11-22-online-extrinsic.md); this one is for `--calibrate-extrinsic` in its
/// first 30 s (docs/notes/2026-12-02-calibration-scenario.md).
Scenario Calibration() {
  Scenario s = Aggressive();
  s.name = "calibration";
  s.description =
      "aggressive's slalom over ten cable covers laid at 45° (roll and pitch as well as yaw): "
      "a drive for the extrinsic calibration";
  for (int i = 0; i < 10; ++i) {
    // Waypoint k = i / 2 + 1 of the slalom (60 + 9k, south road ± 2.5 m), or the crossing
    // half-way to the next one; parallel neighbours are 1.4 m apart, their profiles 1 m long.
    const int k = i / 2 + 1;
    const bool crossing = i % 2 == 1;
    const double side_m = crossing ? 0.0 : (k % 2 == 1 ? 2.5 : -2.5);
    const Eigen::Vector2d centre(60.0 + 9.0 * (k + (crossing ? 0.5 : 0.0)), L::kRoadSouth + side_m);
    const Eigen::Vector2d along = Eigen::Vector2d(1.0, k % 2 == 1 ? 1.0 : -1.0).normalized();
    s.extra_bumps.push_back({centre, along, 0.5, 3.5, 0.05});
  }
  return s;
}

/// The substation part of loop943's patrol (ring and middle roads, no yard), as a polyline.
std::vector<Eigen::Vector2d> PatrolRoads() {
  return {{60.0, L::kRoadSouth},          {L::kRoadEast, L::kRoadSouth},
          {L::kRoadEast, L::kRoadMiddle}, {L::kRoadWest, L::kRoadMiddle},
          {L::kRoadWest, L::kRoadNorth},  {L::kRoadEast, L::kRoadNorth},
          {L::kRoadEast, L::kRoadSouth},  {L::kRoadWest, L::kRoadSouth}};
}

/// `length_m` of `roads` from arc length `s0_m`, forwards (`dir` +1) or backwards (−1), as
/// waypoints: the start point, every corner passed (kept only ≥ 10 m from the start and the
/// end, so that the turn fits), the end point.
std::vector<Eigen::Vector2d> Stretch(const std::vector<Eigen::Vector2d>& roads,
                                     double s0_m,
                                     int dir,
                                     double length_m) {
  std::vector<double> s = {0.0};
  for (size_t i = 1; i < roads.size(); ++i)
    s.push_back(s.back() + (roads[i] - roads[i - 1]).norm());
  const auto at = [&](double a) {
    size_t i = 1;
    while (i + 1 < roads.size() && s[i] < a) ++i;
    const double u = (a - s[i - 1]) / (s[i] - s[i - 1]);
    return Eigen::Vector2d(roads[i - 1] + u * (roads[i] - roads[i - 1]));
  };
  const double s1_m = s0_m + dir * length_m;
  std::vector<Eigen::Vector2d> out = {at(s0_m)};
  for (size_t k = 0; k < roads.size(); ++k) {
    const size_t i = dir > 0 ? k : roads.size() - 1 - k;
    const double d0 = (s[i] - s0_m) * dir, d1 = (s1_m - s[i]) * dir;
    if (d0 >= 10.0 && d1 >= 10.0) out.push_back(roads[i]);
  }
  out.push_back(at(s1_m));
  return out;
}

/// A second patrol of the same substation for relocalization in a saved map (issue 8): it
/// starts at a place on the substation roads drawn from the seed, heading either way, and
/// drives 200 m along them.
Scenario Revisit(uint64_t seed) {
  Scenario s{"revisit",
             "200 m along the substation roads from a start drawn from the seed (either "
             "direction): a second drive for relocalization in a map made on loop943",
             {},
             {},
             {}};
  const std::vector<Eigen::Vector2d> roads = PatrolRoads();
  double total_m = 0.0;
  for (size_t i = 1; i < roads.size(); ++i) total_m += (roads[i] - roads[i - 1]).norm();
  constexpr double kLengthM = 200.0;
  Rng rng(seed ^ 0x5EED5EEDull);
  const double s0_m = rng.Uniform(0.0, total_m);
  int dir = rng.Uniform() < 0.5 ? 1 : -1;
  if (s0_m + dir * kLengthM > total_m || s0_m + dir * kLengthM < 0.0) dir = -dir;
  s.route = Base(1.0, 4.0, Stretch(roads, s0_m, dir, kLengthM));
  return s;
}

/// `loop943`'s patrol in the field (issue 36): every disturbance on (disturb/disturbances.h).
Scenario Field() {
  Scenario s = Loop943();
  s.name = "field";
  s.description =
      "loop943's patrol with every field disturbance: people, vehicles, vibration, mixed "
      "pixels, rain, dust, dropouts, a LiDAR-IMU time offset, IMU temperature drift";
  for (Disturbance d : AllDisturbances()) s.disturb.Add(d);
  return s;
}

}  // namespace

std::vector<std::string> ScenarioNames() {
  return {"short", "loop943", "degenerate", "aggressive", "revisit", "calibration", "field"};
}

std::optional<Scenario> MakeScenario(const std::string& name, uint64_t seed) {
  if (name == "revisit") return Revisit(seed);
  if (name == "short") return Short();
  if (name == "loop943") return Loop943();
  if (name == "degenerate") return Degenerate();
  if (name == "aggressive") return Aggressive();
  if (name == "calibration") return Calibration();
  if (name == "field") return Field();
  return std::nullopt;
}

}  // namespace swlio::sim
