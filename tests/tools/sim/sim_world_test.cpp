#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "scenarios/scenarios.h"
#include "scenarios/sim_setup.h"
#include "swlio/core/lie.h"
#include "world/substation.h"

namespace swlio::sim {
namespace {

TEST(SimWorld, HasEveryClassAndIsDeterministic) {
  const World a = GenerateSubstation(1);
  const World b = GenerateSubstation(1);
  const World c = GenerateSubstation(2);
  ASSERT_EQ(a.primitives().size(), b.primitives().size());
  for (size_t i = 0; i < a.primitives().size(); ++i) {
    EXPECT_EQ(a.primitives()[i].min_xy, b.primitives()[i].min_xy);
  }
  EXPECT_NE(a.terrain.slope, c.terrain.slope);
  for (SurfaceClass cls : {SurfaceClass::kWall, SurfaceClass::kFence, SurfaceClass::kPole,
                           SurfaceClass::kGantry, SurfaceClass::kInsulator, SurfaceClass::kBusbar,
                           SurfaceClass::kTrench, SurfaceClass::kTree}) {
    EXPECT_GT(a.CountOf(cls), 0u) << ClassName(cls);
  }
  EXPECT_GT(a.CountOf(SurfaceClass::kTransformer) + c.CountOf(SurfaceClass::kTransformer), 0u);
}

TEST(SimWorld, RaysHitGroundAndFenceWhereExpected) {
  const World w = GenerateSubstation(3);
  const Eigen::Vector3d o(20.0, 40.0, w.terrain.Height({20.0, 40.0}) + 0.8);
  const RayHit down = w.Cast(o, -Eigen::Vector3d::UnitZ(), 100.0);
  ASSERT_EQ(down.cls, SurfaceClass::kGround);
  EXPECT_NEAR(o.z() - down.range_m, w.terrain.SurfaceHeight({20.0, 40.0}), 1e-4);
  // Horizontally west from the yard: the fence at x = −12 (mesh 2 cm thick, posts inside).
  const RayHit west = w.Cast(o, -Eigen::Vector3d::UnitX(), 100.0);
  EXPECT_EQ(west.cls, SurfaceClass::kFence);
  EXPECT_NEAR(west.range_m, 32.0, 0.2);
  // Straight up: nothing.
  EXPECT_LT(w.Cast(o, Eigen::Vector3d::UnitZ(), 100.0).range_m, 0.0);
}

TEST(SimWorld, SurfaceHeightAndGradientAtOnceEqualsEachApart) {
  // The ray caster uses the combined call; recordings must not change with it.
  const World w = GenerateSubstation(4);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 200; ++i) points.emplace_back(-15.0 + 0.37 * i, 60.0 - 0.29 * i);
  for (const Bump& b : w.terrain.bumps) points.push_back(b.center + 0.2 * b.along);
  ASSERT_FALSE(w.terrain.bumps.empty());
  for (const Eigen::Vector2d& p : points) {
    double h = 0.0;
    Eigen::Vector2d g;
    w.terrain.SurfaceHeightAndGradient(p, &h, &g);
    EXPECT_EQ(h, w.terrain.SurfaceHeight(p)) << p.transpose();
    EXPECT_EQ(g, w.terrain.SurfaceGradient(p)) << p.transpose();
  }
}

TEST(SimRoutes, ScenarioFactsHold) {
  const World w = GenerateSubstation(1);
  for (const std::string& name : ScenarioNames()) {
    const Scenario s = *MakeScenario(name);
    const Trajectory traj(s.route, &w.terrain);
    const Kinematics k0 = traj.At(0.0), k_still = traj.At(1.99);
    EXPECT_EQ(k0.p_world, k_still.p_world) << name << ": stands still for 2 s";
    double max_v = 0.0, max_yaw_rate = 0.0;
    for (double t = 0.0; t < traj.duration_s(); t += 0.05) {
      const Kinematics k = traj.At(t);
      max_v = std::max(max_v, k.v_world.head<2>().norm());
      max_yaw_rate = std::max(max_yaw_rate, std::abs(k.omega_body.z()));
    }
    EXPECT_LE(max_v, 1.5 + 1e-6) << name;
    EXPECT_GE(max_v, 0.3) << name;
    EXPECT_LE(max_yaw_rate, 60.0 * M_PI / 180.0 * 1.1) << name;
  }
  const Trajectory loop(MakeScenario("loop943")->route, &w.terrain);
  EXPECT_NEAR(loop.length_m(), 943.0, 10.0);
  EXPECT_LT((loop.At(0.0).p_world - loop.At(loop.duration_s()).p_world).norm(), 0.5);
  const Trajectory short_route(MakeScenario("short")->route, &w.terrain);
  EXPECT_NEAR(short_route.duration_s(), 60.0, 8.0);
}

/// Velocity, acceleration and body rate agree with central differences of pose: the analytic
/// derivatives the IMU is synthesized from are those of the trajectory itself.
TEST(SimRoutes, DerivativesAreConsistentAndContinuous) {
  const World w = GenerateSubstation(5);
  const Trajectory traj(MakeScenario("aggressive")->route, &w.terrain);
  const double h = 1e-3;
  for (double t = 0.01; t < traj.duration_s() - 0.01; t += 0.0137) {
    const Kinematics k = traj.At(t), km = traj.At(t - h), kp = traj.At(t + h);
    EXPECT_LT((k.v_world - (kp.p_world - km.p_world) / (2 * h)).norm(), 2e-3) << t;
    EXPECT_LT((k.a_world - (kp.v_world - km.v_world) / (2 * h)).norm(), 2e-2) << t;
    const Eigen::Vector3d omega = lie::Log(km.R_world_body.transpose() * kp.R_world_body) / (2 * h);
    EXPECT_LT((k.omega_body - omega).norm(), 2e-3) << t;
  }
  // Continuity: at 1 ms steps the acceleration changes by less than 0.2 m/s² (jerk < 200).
  Eigen::Vector3d prev_a = traj.At(0.0).a_world;
  double max_jump = 0.0;
  for (double t = 0.001; t < traj.duration_s(); t += 0.001) {
    const Eigen::Vector3d a = traj.At(t).a_world;
    max_jump = std::max(max_jump, (a - prev_a).norm());
    prev_a = a;
  }
  EXPECT_LT(max_jump, 0.2) << "acceleration must be continuous (C2 path)";
}

/// RMS of the body's roll and pitch rates over the first `span_s` of a scenario's drive, in the
/// world its setup builds (the calibration course's covers included).
Eigen::Vector2d TiltRateRms(const std::string& scenario, double span_s) {
  const std::optional<SimSetup> setup = MakeSimSetup(scenario, 1);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int n = 0;
  for (double t = 0.0; t < span_s; t += 0.01, ++n) {
    sum += setup->trajectory->At(t).omega_body.head<2>().cwiseAbs2();
  }
  return (sum / n).cwiseSqrt();
}

TEST(SimRoutes, TheCalibrationCourseTipsTheRobotAboutBothHorizontalAxes) {
  const Eigen::Vector2d plain = TiltRateRms("aggressive", 32.0);
  const Eigen::Vector2d course = TiltRateRms("calibration", 32.0);
  std::printf(
      "roll/pitch rate RMS, first 32 s: aggressive %.2f / %.2f °/s, calibration %.2f / %.2f °/s\n",
      plain.x() * 180 / M_PI, plain.y() * 180 / M_PI, course.x() * 180 / M_PI,
      course.y() * 180 / M_PI);
  EXPECT_GT(course.x(), 5.0 * plain.x()) << "roll";
  EXPECT_GT(course.y(), 5.0 * plain.y()) << "pitch";
  // Over the covers too the path stays C2 (no cover's lateral end is driven over).
  const std::optional<SimSetup> setup = MakeSimSetup("calibration", 1);
  Eigen::Vector3d prev_a = setup->trajectory->At(0.0).a_world;
  double max_jump = 0.0;
  for (double t = 0.001; t < 60.0; t += 0.001) {
    const Eigen::Vector3d a = setup->trajectory->At(t).a_world;
    max_jump = std::max(max_jump, (a - prev_a).norm());
    prev_a = a;
  }
  EXPECT_LT(max_jump, 0.2);
  // The covers are the course's own: the substation of every other scenario has none of them.
  const std::optional<SimSetup> aggressive = MakeSimSetup("aggressive", 1);
  EXPECT_EQ(setup->world->terrain.bumps.size(), aggressive->world->terrain.bumps.size() + 10);
  EXPECT_EQ(aggressive->world->terrain.bumps.size(), GenerateSubstation(1).terrain.bumps.size());
}

}  // namespace
}  // namespace swlio::sim
