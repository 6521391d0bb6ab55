#include "scenarios.h"

#include <numbers>

#include "substation.h"

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
  Scenario s{"short", "about 60 s: along the south road, a left turn onto the east road", {}};
  s.route =
      Base(1.2, 4.0, {{150.0, L::kRoadSouth}, {L::kRoadEast, L::kRoadSouth}, {L::kRoadEast, 35.0}});
  return s;
}

Scenario Loop943() {
  Scenario s{"loop943",
             "a 943 m patrol: ring and middle roads, then a loop through the open yard, back to "
             "the start; revisits the east and south roads",
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
             {}};
  s.route = Base(1.2, 4.0, {{20.0, 0.0}, {20.0, 85.0}, {-7.0, 85.0}, {-7.0, -3.0}, {35.0, -3.0}});
  return s;
}

Scenario Aggressive() {
  Scenario s{"aggressive",
             "fast (1.5 m/s) slalom with yaw rates near 60 °/s, over road bumps, sharp corners",
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

}  // namespace

std::vector<std::string> ScenarioNames() {
  return {"short", "loop943", "degenerate", "aggressive"};
}

std::optional<Scenario> MakeScenario(const std::string& name) {
  if (name == "short") return Short();
  if (name == "loop943") return Loop943();
  if (name == "degenerate") return Degenerate();
  if (name == "aggressive") return Aggressive();
  return std::nullopt;
}

}  // namespace swlio::sim
