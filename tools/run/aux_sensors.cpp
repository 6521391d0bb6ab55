#include "aux_sensors.h"

namespace swlio::tools {
namespace {

bool SetUpWheel(const std::filesystem::path& dir,
                daemon::DaemonConfig* config,
                daemon::SensorInputOptions* read,
                std::string* error) {
  config->window.wheel.enabled = true;
  if (!daemon::IsRecordingFolder(dir.string())) {  // a bag: its Odometry topic, --config's frame
    read->bag.wheel = true;
    return true;
  }
  std::optional<drivers::CanConfig> can = daemon::ManifestWheelCan(dir);
  if (!can && config->can.ValidateLayout().empty()) can = config->can;
  if (!can) {
    *error =
        "--wheel on: no CAN layout (neither a wheel: block in the recording's manifest.yaml nor "
        "a valid can: section in --config)";
    return false;
  }
  read->recording.wheel = can;
  if (const auto T = daemon::ManifestWheelExtrinsic(dir)) {
    config->window.wheel.T_imu_base = estimator::ExtrinsicConfig::FromIsometry(*T);
  }
  return true;
}

void SetUpGnss(const std::filesystem::path& dir,
               daemon::DaemonConfig* config,
               daemon::SensorInputOptions* read) {
  estimator::GnssConfig& g = config->loop_closure.gnss;
  g.enabled = true;
  read->recording.gnss = true;
  read->bag.gnss = true;
  if (const auto m = daemon::ManifestGnssSetup(dir)) {
    g.origin_lat_deg = m->origin.lat_deg;
    g.origin_lon_deg = m->origin.lon_deg;
    g.origin_height_m = m->origin.height_m;
    g.antenna_imu_m = m->antenna_imu_m;
  }
}

}  // namespace

bool SetUpAuxSensors(const std::filesystem::path& dir,
                     bool wheel,
                     bool gnss,
                     daemon::DaemonConfig* config,
                     daemon::SensorInputOptions* read,
                     std::string* error) {
  if (wheel && !SetUpWheel(dir, config, read, error)) return false;
  if (gnss) SetUpGnss(dir, config, read);
  return true;
}

}  // namespace swlio::tools
