// People and vehicles (world/actors.h, disturb/actor_setup.h): their motion keeps its bounds,
// they never go through the static world, the robot or each other, they meet the robot, the
// LiDAR sees them where they are, and revisit's parked vehicles stand elsewhere than the mapping
// drive's.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "disturb/actor_clearance.h"
#include "disturb/actor_setup.h"
#include "disturb/apply_disturbances.h"
#include "recording/actors_csv.h"
#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"
#include "sensors/labelled_scan.h"
#include "swlio/core/time.h"
#include "world/actors.h"

namespace swlio::sim {
namespace {

std::optional<SimSetup> WithActors(const std::string& scenario,
                                   uint64_t seed,
                                   std::optional<double> duration_s = std::nullopt,
                                   std::optional<uint64_t> world_seed = std::nullopt) {
  auto setup = MakeSimSetup(scenario, seed, duration_s, world_seed);
  if (setup) ApplyDisturbances(&*setup, *ParseDisturbanceList("people,vehicles", nullptr));
  return setup;
}

/// Point `p_world` in the frame of actor `a` at `t_s`.
Eigen::Vector3d InActorFrame(const Actor& a, double t_s, const Eigen::Vector3d& p_world) {
  const ActorPose pose = a.At(t_s);
  const Eigen::Vector3d r = p_world - pose.ground_m;
  const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
  return {c * r.x() + s * r.y(), -s * r.x() + c * r.y(), r.z()};
}

/// Distance from `p` (actor frame) to the surface of `part`; negative inside.
double SignedDistance(const ActorPart& part, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = (p - part.center_m).cwiseAbs() - part.half_m;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

/// Whether `p` lies inside a static primitive (independent of the footprint checks).
bool InsidePrimitive(const Primitive& pr, const Eigen::Vector3d& p) {
  switch (pr.kind) {
    case Primitive::Kind::kBox: {
      const Eigen::Vector3d r = p - pr.box.center;
      const double c = std::cos(pr.box.yaw_rad), s = std::sin(pr.box.yaw_rad);
      const Eigen::Vector3d l(c * r.x() + s * r.y(), -s * r.x() + c * r.y(), r.z());
      return (l.cwiseAbs().array() <= pr.box.half_m.array()).all();
    }
    case Primitive::Kind::kCylinder: {
      const Eigen::Vector3d axis = pr.cylinder.b - pr.cylinder.a;
      const double h = (p - pr.cylinder.a).dot(axis) / axis.squaredNorm();
      const Eigen::Vector3d radial = p - pr.cylinder.a - h * axis;
      return h >= 0.0 && h <= 1.0 && radial.norm() <= pr.cylinder.radius_m;
    }
    case Primitive::Kind::kSphere:
      return (p - pr.sphere.center).norm() <= pr.sphere.radius_m;
  }
  return false;
}

TEST(SimActors, CountsScaleWithTheDrive) {
  EXPECT_EQ(PeopleCount(60.0), 2);
  EXPECT_EQ(VehicleCount(60.0), 2);
  EXPECT_EQ(PeopleCount(950.0), 8);
  EXPECT_EQ(VehicleCount(950.0), 5);
  auto field = MakeSimSetup("field", 1);
  ASSERT_TRUE(field && field->world->actors);
  int people = 0, vehicles = 0;
  for (const Actor& a : field->world->actors->actors()) {
    (a.plan().kind == ActorKind::kPerson ? people : vehicles) += 1;
  }
  EXPECT_EQ(people, 8) << "every drawn person found a place";
  EXPECT_EQ(vehicles, 5);
  EXPECT_FALSE(MakeSimSetup("loop943", 1)->world->actors) << "off unless asked for";
}

TEST(SimActors, SpeedsStayWithinTheirBounds) {
  auto field = MakeSimSetup("field", 1);
  ASSERT_TRUE(field);
  const ActorSet& set = *field->world->actors;
  constexpr double kDt = 0.02;
  for (const Actor& a : set.actors()) {
    const bool person = a.plan().kind == ActorKind::kPerson;
    if (person) {
      EXPECT_GE(a.plan().cruise_mps, 1.0);
      EXPECT_LE(a.plan().cruise_mps, 1.5);
    } else {
      EXPECT_LE(a.plan().cruise_mps, 5.0);
    }
    double fastest = 0.0;
    Eigen::Vector2d last = a.At(0.0).ground_m.head<2>();
    for (double t = kDt; t <= SimDuration(*field); t += kDt) {
      const ActorPose pose = a.At(t);
      const double speed = (pose.ground_m.head<2>() - last).norm() / kDt;
      last = pose.ground_m.head<2>();
      EXPECT_LE(pose.speed_mps, a.plan().cruise_mps + 1e-9);
      ASSERT_LE(speed, a.plan().cruise_mps + 1e-6) << "actor " << a.id() << " at " << t;
      fastest = std::max(fastest, speed);
    }
    if (set.Moving(a.id())) {
      EXPECT_GT(fastest, 0.9 * a.plan().cruise_mps) << "actor " << a.id() << " reaches cruise";
    } else {
      EXPECT_EQ(fastest, 0.0) << "actor " << a.id() << " stands the whole drive";
    }
  }
}

/// Every part's corners and a grid inside stay out of every primitive; the robot keeps its
/// distance; no two actors overlap. Checked on `field` and on `short` and `revisit`.
TEST(SimActors, NeverThroughTheWorldTheRobotOrEachOther) {
  for (const auto& [name, seed] :
       {std::pair<std::string, uint64_t>{"field", 1}, {"short", 2}, {"revisit", 3}}) {
    auto setup = name == "field" ? MakeSimSetup(name, seed) : WithActors(name, seed);
    ASSERT_TRUE(setup);
    const ActorSet& set = *setup->world->actors;
    const double duration = SimDuration(*setup);
    for (const Actor& a : set.actors()) {
      for (double t = 0.0; t <= duration; t += 0.25) {
        const ActorPose pose = a.At(t);
        const double c = std::cos(pose.yaw_rad), s = std::sin(pose.yaw_rad);
        for (const ActorPart& part : a.plan().parts) {
          for (double u : {-1.0, 0.0, 1.0}) {
            for (double v : {-1.0, 0.0, 1.0}) {
              for (double w : {-0.8, -0.3, 0.3, 1.0}) {
                const Eigen::Vector3d l =
                    part.center_m + part.half_m.cwiseProduct(Eigen::Vector3d(u, v, w));
                const Eigen::Vector3d p =
                    pose.ground_m +
                    Eigen::Vector3d(c * l.x() - s * l.y(), s * l.x() + c * l.y(), l.z());
                for (const Primitive& pr : setup->world->primitives()) {
                  if ((p.head<2>().array() < pr.min_xy.array()).any() ||
                      (p.head<2>().array() > pr.max_xy.array()).any()) {
                    continue;
                  }
                  ASSERT_FALSE(InsidePrimitive(pr, p)) << name << ": actor " << a.id() << " at "
                                                       << t << " s in a " << ClassName(pr.cls);
                }
              }
            }
          }
        }
      }
      for (double t = 0.0; t <= duration; t += 0.02) {
        const Eigen::Vector2d robot = setup->trajectory->At(t).p_world.head<2>();
        ASSERT_GE(Distance(robot, FootprintAt(a, a.At(t))), 0.9)
            << name << ": actor " << a.id() << " at " << t << " s";
        for (const Actor& b : set.actors()) {
          if (b.id() <= a.id() || std::fmod(t, 0.1) > 0.02) continue;
          ASSERT_FALSE(Overlap(FootprintAt(a, a.At(t)), FootprintAt(b, b.At(t))))
              << name << ": actors " << a.id() << " and " << b.id() << " at " << t;
        }
      }
    }
  }
}

TEST(SimActors, FieldHasEveryKindOfBehaviour) {
  auto field = MakeSimSetup("field", 1);
  ASSERT_TRUE(field);
  const ActorSet& set = *field->world->actors;
  const RobotTrack robot = SampleRobot(*field->trajectory);
  const double duration = SimDuration(*field);
  int close_people = 0, close_vehicles = 0, stop_and_go = 0, leaving = 0, parked = 0;
  for (const Actor& a : set.actors()) {
    const bool person = a.plan().kind == ActorKind::kPerson;
    if (MinRobotDistanceM(a, robot) <= 3.0) ++(person ? close_people : close_vehicles);
    const auto& w = a.plan().waypoints_xy;
    for (size_t k = 1; k + 1 < w.size(); ++k) {
      if (a.plan().stop_s[k] > 0.0 && a.ArrivalS(k) > 0.0 && a.ArrivalS(k) < duration) {
        ++stop_and_go;
        break;
      }
    }
    if (!person && set.Moving(a.id()) && a.plan().t_go_s > 30.0 && w.size() == 2) {
      // Stood still from the start, then left during the drive.
      EXPECT_EQ(a.At(0.0).ground_m, a.At(a.plan().t_go_s).ground_m);
      EXPECT_GT((a.At(duration).ground_m - a.At(0.0).ground_m).norm(), 30.0);
      ++leaving;
    }
    if (!person && !set.Moving(a.id())) ++parked;
  }
  EXPECT_GE(close_people, 2) << "people pass within 3 m of the robot";
  EXPECT_GE(close_vehicles, 1) << "vehicles pass within 3 m of the robot";
  EXPECT_GE(stop_and_go, 3);
  EXPECT_GE(leaving, 1) << "a vehicle parked for a while, then leaving";
  EXPECT_GE(parked, 1) << "a vehicle parked all drive";
}

/// The returns on actors lie on one of the actor's parts at their firing time, carry its class
/// and moving flag; both kinds are seen on a short drive.
TEST(SimActors, LidarSeesThemWhereTheyAre) {
  auto setup = WithActors("short", 1, 10.0);
  ASSERT_TRUE(setup);
  const ActorSet& set = *setup->world->actors;
  LidarSimulator lidar(setup->world.get(), setup->trajectory.get(), setup->lidar, 1);
  SimPacket packet;
  std::vector<SimReturn> returns;
  size_t people = 0, vehicles = 0, moving = 0;
  while (lidar.Next(&packet, &returns)) {
    for (const SimReturn& r : returns) {
      if (r.actor == 0) {
        ASSERT_NE(r.cls, SurfaceClass::kPerson);
        ASSERT_NE(r.cls, SurfaceClass::kVehicle);
        ASSERT_FALSE(r.moving);
        continue;
      }
      if (r.true_range_m <= 0.0) continue;
      const Actor& a = set.Get(r.actor);
      ASSERT_EQ(r.cls, a.surface_class());
      ASSERT_EQ(r.moving, set.Moving(r.actor));
      const Eigen::Vector3d p = InActorFrame(a, static_cast<double>(r.t_true_ns) * 1e-9, r.p_world);
      double nearest = 1e9;
      for (const ActorPart& part : a.plan().parts) {
        nearest = std::min(nearest, std::abs(SignedDistance(part, p)));
      }
      ASSERT_LT(nearest, 0.005) << "actor " << r.actor << " at " << r.t_true_ns;
      ++(a.plan().kind == ActorKind::kPerson ? people : vehicles);
      moving += r.moving ? 1 : 0;
    }
  }
  EXPECT_GT(people, 50u);
  EXPECT_GT(vehicles, 500u);
  EXPECT_GT(moving, 50u);
}

TEST(SimActors, LabelledScansMarkMovingPoints) {
  auto setup = WithActors("short", 1, 10.0);
  ASSERT_TRUE(setup);
  LabelledScanSource source(*setup);
  LabelledScan ls;
  size_t moving = 0, on_actors = 0;
  while (source.Next(&ls, 0.0)) {
    ASSERT_EQ(ls.moving.size(), ls.scan.points.size());
    for (size_t i = 0; i < ls.moving.size(); ++i) {
      const bool actor = ls.cls[i] == SurfaceClass::kPerson || ls.cls[i] == SurfaceClass::kVehicle;
      on_actors += actor ? 1 : 0;
      moving += ls.moving[i];
      if (ls.moving[i] != 0) {
        ASSERT_TRUE(actor);
      }
    }
  }
  EXPECT_GT(moving, 0u);
  EXPECT_GT(on_actors, moving) << "the parked vehicle's points are not moving";
}

TEST(SimActors, SameSeedSameActorsAndPackets) {
  auto a = WithActors("short", 4, 6.0);
  auto b = WithActors("short", 4, 6.0);
  auto c = WithActors("short", 5, 6.0);
  ASSERT_TRUE(a && b && c);
  auto csv = [](const SimSetup& s) {
    std::ostringstream out;
    WriteActorsCsv(
        *s.world->actors, SimDuration(s), [](double t) { return SecToNs(t); }, out);
    return out.str();
  };
  EXPECT_EQ(csv(*a), csv(*b));
  EXPECT_NE(csv(*a), csv(*c));
  LidarSimulator la(a->world.get(), a->trajectory.get(), a->lidar, 4);
  LidarSimulator lb(b->world.get(), b->trajectory.get(), b->lidar, 4);
  SimPacket pa, pb;
  for (int i = 0; i < 1500 && la.Next(&pa); ++i) {
    ASSERT_TRUE(lb.Next(&pb));
    ASSERT_EQ(pa.bytes, pb.bytes) << "packet " << i;
  }
}

TEST(SimActors, RecordingWritesActorsCsv) {
  const auto dir = std::filesystem::temp_directory_path() / "swlio_sim_actors_test";
  std::filesystem::remove_all(dir);
  auto setup = WithActors("short", 1, 4.0);
  ASSERT_TRUE(setup);
  RecordingStats stats;
  std::string error;
  ASSERT_TRUE(WriteRecording(*setup, dir, &stats, &error)) << error;
  std::ifstream in(dir / "actors.csv");
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "t_ns,id,kind,moves,x_m,y_m,z_m,yaw_rad,half_x_m,half_y_m,half_z_m");
  const ActorSet& set = *setup->world->actors;
  size_t rows = 0;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string t_ns, id, kind, moves, rest;
    std::getline(fields, t_ns, ',');
    std::getline(fields, id, ',');
    std::getline(fields, kind, ',');
    std::getline(fields, moves, ',');
    const Actor& a = set.Get(static_cast<uint16_t>(std::stoi(id)));
    EXPECT_EQ(std::stoll(t_ns),
              kFileHostStartNs + static_cast<int64_t>(rows / set.actors().size()) * 100'000'000);
    EXPECT_EQ(kind, ActorKindName(a.plan().kind));
    EXPECT_EQ(moves, set.Moving(a.id()) ? "1" : "0");
    double v[7];
    for (double& x : v) {
      ASSERT_TRUE(std::getline(fields, rest, ','));
      x = std::stod(rest);
    }
    EXPECT_NEAR(v[6], a.bounds().half_m.z(), 1e-3);
    ++rows;
  }
  EXPECT_EQ(rows, 41 * set.actors().size());
  EXPECT_GE(set.actors().size(), 2u);
  std::ifstream manifest(dir / "manifest.yaml");
  std::stringstream text;
  text << manifest.rdbuf();
  size_t people = 0, parked = 0;
  for (const Actor& a : set.actors()) {
    people += a.plan().kind == ActorKind::kPerson ? 1 : 0;
    parked += a.plan().kind == ActorKind::kVehicle && !set.Moving(a.id()) ? 1 : 0;
  }
  EXPECT_GE(people, 1u);
  EXPECT_GE(parked, 1u);
  EXPECT_NE(text.str().find("actor_people: " + std::to_string(people) + "\n"), std::string::npos)
      << text.str();
  EXPECT_NE(text.str().find("actor_vehicles_parked_all_drive: " + std::to_string(parked) + "\n"),
            std::string::npos);

  std::filesystem::remove_all(dir);
  auto plain = MakeSimSetup("short", 1, 2.0);
  ASSERT_TRUE(WriteRecording(*plain, dir, &stats, &error)) << error;
  EXPECT_FALSE(std::filesystem::exists(dir / "actors.csv"));
  std::filesystem::remove_all(dir);
}

/// `revisit --seed 2 --world-seed 1 --disturb vehicles` is field 1's substation a day later:
/// its vehicles parked all drive stand where none stood on the mapping drive.
TEST(SimActors, RevisitParksVehiclesElsewhere) {
  auto mapping = MakeSimSetup("field", 1);
  ASSERT_TRUE(mapping);
  for (uint64_t seed = 2; seed <= 6; ++seed) {
    auto revisit = MakeSimSetup("revisit", seed, std::nullopt, uint64_t{1});
    ASSERT_TRUE(revisit);
    ApplyDisturbances(&*revisit, *ParseDisturbanceList("vehicles", nullptr));
    const ActorSet& now = *revisit->world->actors;
    int parked = 0;
    for (const Actor& a : now.actors()) {
      if (now.Moving(a.id())) continue;
      ++parked;
      for (const Actor& b : mapping->world->actors->actors()) {
        if (mapping->world->actors->Moving(b.id())) continue;
        EXPECT_GT((a.At(0.0).ground_m - b.At(0.0).ground_m).norm(), 5.0) << "seed " << seed;
      }
    }
    EXPECT_GE(parked, 1) << "seed " << seed;
  }
}

}  // namespace
}  // namespace swlio::sim
