#include "disturb/actor_setup.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "disturb/actor_clearance.h"
#include "disturb/actor_roles.h"
#include "rng.h"

namespace swlio::sim {
namespace {

/// Tries per actor: the first half anchored in its own share of the drive, then anywhere.
constexpr int kTries = 80;

constexpr ActorRole kPersonRoles[] = {ActorRole::kCrossing, ActorRole::kWalking,
                                      ActorRole::kInspecting, ActorRole::kWalking};
constexpr ActorRole kVehicleRoles[] = {ActorRole::kOncoming,       ActorRole::kParkedAllDrive,
                                       ActorRole::kParkedLeaving,  ActorRole::kOvertaking,
                                       ActorRole::kParkedAllDrive, ActorRole::kOncoming};

/// The robot at `t_s`, or nothing while it stands (no heading to meet it along).
std::optional<RobotAnchor> AnchorAt(const Trajectory& trajectory, double t_s) {
  const Kinematics k = trajectory.At(t_s);
  if (k.v_world.head<2>().norm() < 0.3) return std::nullopt;
  RobotAnchor a;
  a.t_s = t_s;
  a.xy = k.p_world.head<2>();
  a.heading = k.v_world.head<2>().normalized();
  a.left = Eigen::Vector2d(-a.heading.y(), a.heading.x());
  return a;
}

struct Drawer {
  SimSetup* setup;
  const ActorClearance* clearance;
  ActorSet* set;
  Rng rng;
  int count = 0;

  /// Draws actor `k` of `count` (role `role`) and adds it; false when no try fitted.
  template <typename Draw>
  bool DrawOne(int k, ActorRole role, Draw draw) {
    const double duration = SimDuration(*setup);
    // Anchors keep 3 s from the drive's ends (a tenth of a short drive's length).
    const double lo = std::min(3.0, 0.1 * duration), span = duration - 2.0 * lo;
    for (int i = 0; i < kTries; ++i) {
      const double u = i < kTries / 2 ? (k + rng.Uniform()) / count : rng.Uniform();
      const std::optional<RobotAnchor> anchor = AnchorAt(*setup->trajectory, lo + u * span);
      if (!anchor) continue;
      std::optional<ActorPlan> plan = draw(role, *anchor, rng);
      if (!plan) continue;
      const Actor candidate(static_cast<uint16_t>(set->actors().size() + 1), *plan,
                            &setup->world->terrain);
      if (clearance->ClearOfWorld(candidate) && clearance->ClearOfRobot(candidate) &&
          clearance->ClearOfActors(candidate, *set)) {
        set->Add(std::move(*plan));
        return true;
      }
    }
    return false;
  }
};

template <typename Draw, size_t N>
void SetUpActors(
    SimSetup* setup, uint64_t salt, int count, const ActorRole (&roles)[N], Draw draw) {
  World& world = *setup->world;
  auto set = world.actors ? std::make_shared<ActorSet>(*world.actors)
                          : std::make_shared<ActorSet>(&world.terrain, SimDuration(*setup));
  const RobotTrack robot = SampleRobot(*setup->trajectory);
  const ActorClearance clearance(&world, &robot);
  Drawer drawer{setup, &clearance, set.get(), Rng(setup->seed ^ salt), count};
  for (int k = 0; k < count; ++k) drawer.DrawOne(k, roles[static_cast<size_t>(k) % N], draw);
  world.actors = std::move(set);
}

}  // namespace

int PeopleCount(double duration_s) {
  return std::clamp(static_cast<int>(1.0 + duration_s / 120.0), 2, 9);
}

int VehicleCount(double duration_s) {
  return std::clamp(static_cast<int>(1.5 + duration_s / 220.0), 2, 6);
}

void SetUpPeople(SimSetup* setup) {
  SetUpActors(setup, 0xBE0B1Eull, PeopleCount(SimDuration(*setup)), kPersonRoles, DrawPerson);
}

void SetUpVehicles(SimSetup* setup) {
  SetUpActors(setup, 0x7A4C5ull, VehicleCount(SimDuration(*setup)), kVehicleRoles, DrawVehicle);
}

}  // namespace swlio::sim
