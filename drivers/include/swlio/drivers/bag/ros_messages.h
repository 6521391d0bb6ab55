#pragma once
/// @file
/// The ROS messages swlio reads from bags, as plain structs (fields as the message definitions
/// name them, units and frames as their comments state; research/bags.md §5). Views
/// (`std::string_view`, `std::span`) point into the serialized message and are valid as long
/// as its bytes are (until the bag reader's next Next()).
///
/// Packet-carrying LiDAR messages of every supported driver become one `LidarPacketsMsg`: the
/// raw UDP payloads that swlio's own decoders (rs16_decoder.h, helios16p_decoder.h,
/// vlp16_decoder.h) read from the network, so a bag decodes exactly like a capture.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "swlio/drivers/bag/message_reader.h"

namespace swlio::drivers::bag {

/// Which message type a topic carries, as far as swlio reads it.
enum class RosMessageKind : uint8_t {
  kUnknown,
  /// rslidar_msg/RslidarScan (rslidar_msg ≤ v1.4) or ROS 1 rslidar_msgs/rslidarScan:
  /// Header + packets[] of {Time stamp; uint8[1248] data}.
  kRslidarScan,
  /// rslidar_msg/RslidarPacket ≤ v1.4 or ROS 1 rslidar_msgs/rslidarPacket: {Time; uint8[1248]}.
  kRslidarPacketLegacy,
  /// rslidar_msg/RslidarPacket ≥ v1.5: {Header; uint8 is_difop; uint8 is_frame_begin; uint8[]}.
  kRslidarPacket,
  /// rslidar_msg/RslidarPacket without a stored definition: legacy when the message is exactly
  /// the legacy size (1260 bytes in CDR, 1256 in ROS 1), else ≥ v1.5 (research/bags.md §2.2).
  kRslidarPacketEither,
  /// robosense_msgs/RobosenseScan (nebula): Header + packets[] of
  /// {Time stamp; uint8 is_difop; uint8[1500] data; uint32 size}.
  kRobosenseScan,
  /// velodyne_msgs/VelodyneScan: Header + packets[] of {Time stamp; uint8[1206] data}.
  kVelodyneScan,
  kPointCloud2,   ///< sensor_msgs/PointCloud2
  kImu,           ///< sensor_msgs/Imu
  kNavSatFix,     ///< sensor_msgs/NavSatFix
  kOdometry,      ///< nav_msgs/Odometry
  kTwistStamped,  ///< geometry_msgs/TwistStamped
};

/// Short name for messages and `swlio-bag info` ("RslidarScan", "Imu", …).
const char* KindName(RosMessageKind kind);

/// What one packet in a LiDAR packet message is, when the message says so.
enum class PacketRole : uint8_t { kUnstated, kData, kInfo };

struct LidarPacketView {
  /// The packet's own stamp, ns; 0 when the bag left it zero (the washing_house bag does).
  int64_t stamp_ns = 0;
  std::span<const uint8_t> payload;         ///< the UDP payload (1248 B RoboSense, 1206 B Velodyne)
  PacketRole role = PacketRole::kUnstated;  ///< RoboSense is_difop when the message has it
};

/// Any packet-carrying LiDAR message: a scan of packets, or one packet.
struct LidarPacketsMsg {
  bool has_header = false;  ///< false for the legacy single-packet type (stamp only)
  RosHeader header;
  std::vector<LidarPacketView> packets;
};

/// sensor_msgs/Imu. Covariances are row-major; all zero = unknown; element 0 = −1 = the
/// quantity is not provided (sensor_msgs/msg/Imu.msg).
struct ImuMsg {
  RosHeader header;
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< frame_id in the world
  std::array<double, 9> orientation_covariance{};
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();  ///< in frame_id
  std::array<double, 9> angular_velocity_covariance{};
  /// Specific force in frame_id, m/s², gravity included (the Xsens driver publishes the
  /// calibrated accelerometer; research/bags.md §7).
  Eigen::Vector3d linear_acceleration_mps2 = Eigen::Vector3d::Zero();
  std::array<double, 9> linear_acceleration_covariance{};
};

/// sensor_msgs/NavSatFix.
struct NavSatFixMsg {
  RosHeader header;
  int8_t status = -1;    ///< −1 no fix, 0 fix, 1 SBAS, 2 GBAS (Jazzy: −2 unknown)
  uint16_t service = 0;  ///< bitmask: GPS 1, GLONASS 2, COMPASS 4, GALILEO 8
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double altitude_m = 0.0;                         ///< above the WGS-84 ellipsoid; NaN when unknown
  std::array<double, 9> position_covariance_m2{};  ///< ENU, row-major
  uint8_t position_covariance_type = 0;  ///< 0 unknown, 1 approximated, 2 diagonal, 3 known
};

/// nav_msgs/Odometry: pose of child_frame_id in header.frame_id, twist in child_frame_id.
struct OdometryMsg {
  RosHeader header;
  std::string_view child_frame_id;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  std::array<double, 36> pose_covariance{};
  Eigen::Vector3d linear_velocity_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();
  std::array<double, 36> twist_covariance{};
};

/// geometry_msgs/TwistStamped: velocity of header.frame_id.
struct TwistStampedMsg {
  RosHeader header;
  Eigen::Vector3d linear_velocity_mps = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity_radps = Eigen::Vector3d::Zero();
};

/// geometry_msgs/TransformStamped: the pose of child_frame_id in header.frame_id.
struct TransformStampedMsg {
  RosHeader header;
  std::string_view child_frame_id;
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};

/// sensor_msgs/PointField datatypes.
enum class PointFieldType : uint8_t {
  kInt8 = 1,
  kUint8 = 2,
  kInt16 = 3,
  kUint16 = 4,
  kInt32 = 5,
  kUint32 = 6,
  kFloat32 = 7,
  kFloat64 = 8,
};

struct PointFieldView {
  std::string_view name;
  uint32_t offset = 0;   ///< bytes from the start of a point
  uint8_t datatype = 0;  ///< PointFieldType, unchecked
  uint32_t count = 0;
};

/// sensor_msgs/PointCloud2 as stored; `point_cloud_points.h` turns it into points.
struct PointCloud2Msg {
  RosHeader header;
  uint32_t height = 0;
  uint32_t width = 0;
  std::vector<PointFieldView> fields;
  bool is_bigendian = false;
  uint32_t point_step = 0;
  uint32_t row_step = 0;
  std::span<const uint8_t> data;
  bool is_dense = false;
};

}  // namespace swlio::drivers::bag
