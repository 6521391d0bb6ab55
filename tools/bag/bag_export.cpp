// swlio-bag export: a recording folder as a rosbag2 MCAP (bag_export.h).

#include "bag_export.h"

#include <Eigen/Geometry>
#include <fstream>
#include <map>
#include <memory>
#include <vector>

#include "swlio/daemon/config/config_loader.h"
#include "swlio/daemon/config/config_printer.h"
#include "swlio/daemon/recording/recording_reader.h"
#include "swlio/drivers/bag/mcap_writer.h"
#include "swlio/drivers/bag/message_encoder.h"
#include "swlio/drivers/bag/point_cloud_writer.h"
#include "swlio/drivers/bag/ros2msg_schema.h"

namespace swlio::tools {
namespace bag = drivers::bag;
namespace {

constexpr auto kCdr = bag::MessageEncoding::kCdr;
constexpr const char* kLidarFrame = "rslidar";  // rslidar_sdk's default ros_frame_id
constexpr const char* kImuFrame = "imu_link";   // the Xsens ROS 2 driver's default frame_id
constexpr const char* kBaseFrame = "base_link";
constexpr const char* kOdomFrame = "odom";

/// rosbag2's `offered_qos_profiles` channel metadata (the YAML list rosbag2 stores, as in the
/// washing_house bag's topics table): keep last `depth`, reliable, volatile or transient local
/// (rmw enums: history 1 = keep last, reliability 1 = reliable, durability 1 = transient local,
/// 2 = volatile), infinite deadline, lifespan and lease.
std::string QosProfile(int depth, bool transient_local) {
  const std::string infinite = "\n    sec: 9223372036\n    nsec: 854775807";
  return "- history: 1\n  depth: " + std::to_string(depth) +
         "\n  reliability: 1\n  durability: " + (transient_local ? "1" : "2") +
         "\n  deadline:" + infinite + "\n  lifespan:" + infinite +
         "\n  liveliness: 1\n  liveliness_lease_duration:" + infinite +
         "\n  avoid_ros_namespace_conventions: false";
}

class McapOut {
 public:
  explicit McapOut(std::unique_ptr<bag::McapWriter> w) : w_(std::move(w)) {}
  /// A channel of ROS type `type` (with its schema) on `topic`.
  uint16_t Channel(const std::string& topic, const std::string& type, bool transient_local) {
    auto s = schemas_.find(type);
    if (s == schemas_.end())
      s = schemas_.emplace(type, w_->AddSchema(type, "ros2msg", bag::Ros2MsgSchema(type))).first;
    return w_->AddChannel(
        s->second, topic, "cdr",
        {{"offered_qos_profiles", QosProfile(transient_local ? 1 : 10, transient_local)},
         {"topic_type_hash", ""}});
  }
  bool Write(uint16_t channel, int64_t t_ns, const std::vector<uint8_t>& data) {
    if (t_ns < 0) {
      negative_time_ = true;
      return false;
    }
    return w_->Write(channel, t_ns, t_ns, data);
  }
  bool Close(std::string* error) {
    if (negative_time_) {
      *error = "the recording has times before the Unix epoch; MCAP cannot store them";
      return false;
    }
    return w_->Close(error);
  }

 private:
  std::unique_ptr<bag::McapWriter> w_;
  std::map<std::string, uint16_t> schemas_;
  bool negative_time_ = false;
};

bag::ImuMsg ImuMessage(const ImuSample& s) {
  bag::ImuMsg m;
  m.header = {s.t_ns, kImuFrame};
  m.orientation_covariance[0] = -1.0;  // no orientation (sensor_msgs/Imu.msg)
  m.angular_velocity_radps = s.gyro_radps;
  m.linear_acceleration_mps2 = s.acc_mps2;
  return m;
}

bag::NavSatFixMsg FixMessage(const GnssFix& f) {
  bag::NavSatFixMsg m;
  m.header = {f.t_ns, "gnss"};
  m.status = f.fix_type >= 2 ? 0 : -1;  // STATUS_FIX / STATUS_NO_FIX
  m.service = 1;                        // SERVICE_GPS
  m.latitude_deg = f.lat_deg;
  m.longitude_deg = f.lon_deg;
  m.altitude_m = f.height_m;
  m.position_covariance_m2 = {f.h_acc_m * f.h_acc_m, 0, 0, 0, f.h_acc_m * f.h_acc_m, 0, 0, 0,
                              f.v_acc_m * f.v_acc_m};
  m.position_covariance_type = 2;  // COVARIANCE_TYPE_DIAGONAL_KNOWN
  return m;
}

bag::OdometryMsg WheelMessage(const WheelOdometry& w) {
  bag::OdometryMsg m;
  m.header = {w.t_ns, kOdomFrame};
  m.child_frame_id = kBaseFrame;
  // Twist only: the pose is not integrated here, so its variance is given as huge.
  for (size_t i = 0; i < 6; ++i) m.pose_covariance[i * 7] = 1e9;
  m.linear_velocity_mps = Eigen::Vector3d(w.linear_velocity_mps, 0.0, 0.0);
  m.angular_velocity_radps = Eigen::Vector3d(0.0, 0.0, w.yaw_rate_radps);
  return m;
}

bag::TransformStampedMsg Transform(int64_t t_ns, const char* child, const Eigen::Isometry3d& T) {
  bag::TransformStampedMsg m;
  m.header = {t_ns, kImuFrame};
  m.child_frame_id = child;
  m.translation_m = T.translation();
  m.rotation = Eigen::Quaterniond(T.linear());
  return m;
}

/// `config` with the recording's rig from its manifest: what a run of the bag needs and the
/// bag cannot carry.
daemon::DaemonConfig WithRig(const std::filesystem::path& dir, daemon::DaemonConfig config) {
  config.lidar = daemon::WithManifestPorts(dir, config.lidar);
  if (const auto T = daemon::ManifestExtrinsic(dir))
    config.estimator.extrinsic_imu_lidar = estimator::ExtrinsicConfig::FromIsometry(*T);
  if (const auto T = daemon::ManifestWheelExtrinsic(dir))
    config.window.wheel.T_imu_base = estimator::ExtrinsicConfig::FromIsometry(*T);
  if (const auto m = daemon::ManifestGnssSetup(dir)) {
    estimator::GnssConfig& g = config.loop_closure.gnss;
    g.origin_lat_deg = m->origin.lat_deg;
    g.origin_lon_deg = m->origin.lon_deg;
    g.origin_height_m = m->origin.height_m;
    g.antenna_imu_m = m->antenna_imu_m;
  }
  return config;
}

}  // namespace

std::string RigConfigPath(const std::string& out) {
  const std::filesystem::path p(out);
  return (p.parent_path() / (p.stem().string() + ".swlio.yaml")).string();
}

bool ExportRecording(const std::filesystem::path& dir,
                     const std::string& out,
                     const ExportOptions& options,
                     ExportCounts* counts,
                     std::string* error) {
  daemon::DaemonConfig config;
  if (!options.config.empty()) {
    const auto loaded = daemon::LoadConfigFile(options.config);
    if (!loaded.ok()) {
      *error = loaded.ErrorReport();
      return false;
    }
    config = loaded.config;
  }
  config = WithRig(dir, config);
  std::ofstream rig(RigConfigPath(out));
  rig << "# The rig of the recording " << dir.string() << " (exported to " << out
      << "): swlio-run BAG --config THIS_FILE\n"
      << daemon::PrintConfig(config);
  if (!rig) {
    *error = "cannot write " + RigConfigPath(out);
    return false;
  }
  daemon::RecordingReadOptions read;
  read.gnss = daemon::ManifestGnssSetup(dir).has_value();
  read.wheel = daemon::ManifestWheelCan(dir);
  auto reader = daemon::RecordingReader::Open(dir, config.lidar, config.imu, read, error);
  if (!reader) return false;
  bag::McapWriterOptions wo;
  wo.compression = options.compression;
  auto writer = bag::McapWriter::Create(out, wo, error);
  if (!writer) return false;
  McapOut mcap(std::move(writer));
  const uint16_t tf_static = mcap.Channel("/tf_static", "tf2_msgs/msg/TFMessage", true);
  const uint16_t clouds = mcap.Channel("/rslidar_points", "sensor_msgs/msg/PointCloud2", false);
  const uint16_t imu = mcap.Channel("/imu/data", "sensor_msgs/msg/Imu", false);
  const uint16_t gnss = read.gnss ? mcap.Channel("/gnss", "sensor_msgs/msg/NavSatFix", false) : 0;
  const uint16_t wheel = read.wheel ? mcap.Channel("/odom", "nav_msgs/msg/Odometry", false) : 0;

  const Eigen::Isometry3d T_imu_lidar = config.estimator.extrinsic_imu_lidar.ToIsometry();
  const Eigen::Isometry3d T_imu_base = config.window.wheel.T_imu_base.ToIsometry();
  bag::OwnedPointCloud2 cloud;
  daemon::RecordingEvent e;
  bool first = true, ok = true;
  while (ok && reader->Next(&e)) {
    const int64_t t_ns = e.kind == daemon::RecordingEvent::Kind::kScan ? e.scan.t_end_ns : e.t_ns();
    if (first) {  // the rig, once, at the first message's time
      std::vector<bag::TransformStampedMsg> tf = {Transform(t_ns, kLidarFrame, T_imu_lidar)};
      if (read.wheel) tf.push_back(Transform(t_ns, kBaseFrame, T_imu_base));
      ok = mcap.Write(tf_static, t_ns, bag::EncodeTfMessage(tf, kCdr));
      first = false;
    }
    switch (e.kind) {
      case daemon::RecordingEvent::Kind::kScan:
        bag::RslidarCloudFromScan(e.scan, kLidarFrame, &cloud);
        ok = ok && mcap.Write(clouds, t_ns, bag::EncodePointCloud2(cloud.msg, kCdr));
        ++counts->clouds;
        break;
      case daemon::RecordingEvent::Kind::kImu:
        ok = ok && mcap.Write(imu, t_ns, bag::EncodeImu(ImuMessage(e.imu), kCdr));
        ++counts->imu;
        break;
      case daemon::RecordingEvent::Kind::kGnss:
        ok = ok && mcap.Write(gnss, t_ns, bag::EncodeNavSatFix(FixMessage(e.gnss), kCdr));
        ++counts->gnss;
        break;
      case daemon::RecordingEvent::Kind::kWheel:
        ok = ok && mcap.Write(wheel, t_ns, bag::EncodeOdometry(WheelMessage(e.wheel), kCdr));
        ++counts->wheel;
        break;
    }
  }
  if (!mcap.Close(error)) return false;
  if (!ok) *error = "cannot write " + out;
  return ok;
}

}  // namespace swlio::tools
