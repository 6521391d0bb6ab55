#include "disturb/disturbance_manifest.h"

#include <sstream>

#include "disturb/weather_setup.h"
#include "swlio/core/exact_number.h"
#include "world/actors.h"

namespace swlio::sim {

std::string DisturbanceManifestBlock(const SimSetup& setup) {
  std::ostringstream y;
  y << "disturbances:  # field disturbances (swlio-sim --disturb), issue 36\n"
    << "  list: " << setup.disturb.ToString() << "\n";
  if (setup.disturb.Has(Disturbance::kTimeOffset)) {
    y << "  # each IMU sample measures the motion of time_offset_s before the host time its\n"
      << "  # SampleTimeFine maps to: the estimator should find it as the IMU-LiDAR offset\n"
      << "  time_offset_s: " << ExactNumber(setup.imu.time_offset_s) << "\n";
  }
  if (const ChassisVibration* v = setup.trajectory->vibration()) {
    y << "  # chassis vibration (scenarios/chassis_vibration.h): acceleration RMS standing and\n"
      << "  # at vibration_reference_speed_mps; tones in vibration_band_hz\n"
      << "  vibration_rest_rms_mps2: " << ExactNumber(v->spec().rest_rms_mps2) << "\n"
      << "  vibration_drive_rms_mps2: " << ExactNumber(v->spec().drive_rms_mps2) << "\n"
      << "  vibration_reference_speed_mps: " << ExactNumber(v->spec().reference_speed_mps) << "\n"
      << "  vibration_band_hz: [" << ExactNumber(v->spec().min_hz) << ", "
      << ExactNumber(v->spec().max_hz) << "]\n"
      << "  vibration_seed: " << v->seed() << "  # the tones' (the drive's seed unless set)\n"
      << "  vibration_motor_hz: [";
    const std::vector<double> hz = v->MotorFrequenciesHz();
    for (size_t i = 0; i < hz.size(); ++i) y << (i ? ", " : "") << ExactNumber(hz[i]);
    y << "]\n";
  }
  if (setup.world->actors) {
    int people = 0, people_moving = 0, vehicles = 0, vehicles_moving = 0;
    for (const Actor& a : setup.world->actors->actors()) {
      const bool moving = setup.world->actors->Moving(a.id());
      (a.plan().kind == ActorKind::kPerson ? people : vehicles) += 1;
      (a.plan().kind == ActorKind::kPerson ? people_moving : vehicles_moving) += moving ? 1 : 0;
    }
    y << "  # people and vehicles (actors.csv), drawn from the drive's seed; moving: they move\n"
      << "  # at some time during the drive (the returns labelled moving come from them)\n"
      << "  actor_people: " << people << "\n"
      << "  actor_people_moving: " << people_moving << "\n"
      << "  actor_vehicles: " << vehicles << "\n"
      << "  actor_vehicles_moving: " << vehicles_moving << "\n"
      << "  actor_vehicles_parked_all_drive: " << vehicles - vehicles_moving << "\n";
  }
  y << WeatherManifestLines(setup);
  return y.str();
}

}  // namespace swlio::sim
