#pragma once
/// @file
/// The messages swlio publishes, as plain C++ values that mirror the ROS 2 messages field for
/// field (the IDL in ipc/idl/ is the wire layout; this header never sees Cyclone DDS).
///
/// Topics, their ROS 2 types and DDS type names (`<pkg>::msg::dds_::<Type>_`):
/// - kPose: geometry_msgs/msg/PoseWithCovarianceStamped,
///   geometry_msgs::msg::dds_::PoseWithCovarianceStamped_
/// - kOdometry: nav_msgs/msg/Odometry, nav_msgs::msg::dds_::Odometry_
/// - kHealth: diagnostic_msgs/msg/DiagnosticArray, diagnostic_msgs::msg::dds_::DiagnosticArray_
/// - kPath: nav_msgs/msg/Path, nav_msgs::msg::dds_::Path_
/// - kMap: sensor_msgs/msg/PointCloud2, sensor_msgs::msg::dds_::PointCloud2_
/// - kOdomOdometry: nav_msgs/msg/Odometry in the odom frame (REP 105: continuous)
/// - kTf, kTfStatic: tf2_msgs/msg/TFMessage, tf2_msgs::msg::dds_::TFMessage_ (/tf, /tf_static)
/// - kSweep: sensor_msgs/msg/PointCloud2, the current de-skewed, registered sweep (for viewers)
///
/// Stamps: `t_ns` is carried as builtin_interfaces/Time (sec = floor(t_ns / 1e9), nanosec =
/// the remainder), so every t_ns whose seconds fit an int32 round-trips exactly. Which clock
/// t_ns is on is the caller's choice; ipc passes it through unchanged.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace swlio::ipc {

/// The topics of IpcConfig.
enum class Topic : uint8_t {
  kPose = 0,
  kOdometry = 1,
  kHealth = 2,
  kPath = 3,
  kMap = 4,
  kOdomOdometry = 5,
  kTf = 6,
  kTfStatic = 7,
  kSweep = 8
};
inline constexpr int kTopicCount = 9;

/// Row-major 6x6 covariance over (x, y, z, rotation about X, Y, Z), as in
/// geometry_msgs/PoseWithCovariance and TwistWithCovariance.
using Covariance6 = std::array<double, 36>;

/// geometry_msgs/Pose: position (Point) and orientation (Quaternion, ROS order x, y, z, w).
struct Pose {
  std::array<double, 3> position_m{};
  std::array<double, 4> orientation_xyzw{0.0, 0.0, 0.0, 1.0};
};

/// geometry_msgs/Twist: linear and angular velocity (Vector3 each).
struct Twist {
  std::array<double, 3> linear_mps{};
  std::array<double, 3> angular_radps{};
};

/// geometry_msgs/PoseWithCovarianceStamped: pose of `frame_id`'s child (the body) in frame_id.
struct PoseWithCovarianceStamped {
  int64_t t_ns = 0;
  std::string frame_id;
  Pose pose;
  Covariance6 covariance{};
};

/// geometry_msgs/PoseStamped (an element of nav_msgs/Path).
struct PoseStamped {
  int64_t t_ns = 0;
  std::string frame_id;
  Pose pose;
};

/// nav_msgs/Odometry: pose in frame_id, twist in child_frame_id (ROS convention).
struct Odometry {
  int64_t t_ns = 0;
  std::string frame_id;
  std::string child_frame_id;
  Pose pose;
  Covariance6 pose_covariance{};
  Twist twist;
  Covariance6 twist_covariance{};
};

/// geometry_msgs/Transform: translation (Vector3) and rotation (Quaternion, x, y, z, w).
struct Transform {
  std::array<double, 3> translation_m{};
  std::array<double, 4> rotation_xyzw{0.0, 0.0, 0.0, 1.0};
};

/// geometry_msgs/TransformStamped: the pose of `child_frame_id` in `frame_id` at `t_ns`
/// (T_frame_child: maps points from the child frame into the parent frame).
struct TransformStamped {
  int64_t t_ns = 0;
  std::string frame_id;
  std::string child_frame_id;
  Transform transform;
};

/// tf2_msgs/TFMessage: the transforms of one /tf or /tf_static sample.
struct TFMessage {
  std::vector<TransformStamped> transforms;
};

/// diagnostic_msgs/DiagnosticStatus level (a ROS `byte`; other values pass through).
enum class DiagnosticLevel : uint8_t { kOk = 0, kWarn = 1, kError = 2, kStale = 3 };

/// diagnostic_msgs/KeyValue.
struct KeyValue {
  std::string key;
  std::string value;
};

/// diagnostic_msgs/DiagnosticStatus.
struct DiagnosticStatus {
  DiagnosticLevel level = DiagnosticLevel::kOk;
  std::string name;
  std::string message;
  std::string hardware_id;
  std::vector<KeyValue> values;
};

/// diagnostic_msgs/DiagnosticArray.
struct DiagnosticArray {
  int64_t t_ns = 0;
  std::string frame_id;
  std::vector<DiagnosticStatus> status;
};

/// nav_msgs/Path: keyframe poses.
struct Path {
  int64_t t_ns = 0;
  std::string frame_id;
  std::vector<PoseStamped> poses;
};

/// sensor_msgs/PointField datatype (a ROS `uint8`; other values pass through).
enum class PointFieldType : uint8_t {
  kInt8 = 1,
  kUint8 = 2,
  kInt16 = 3,
  kUint16 = 4,
  kInt32 = 5,
  kUint32 = 6,
  kFloat32 = 7,
  kFloat64 = 8
};

/// sensor_msgs/PointField: one named field of every point.
struct PointField {
  std::string name;
  uint32_t offset = 0;  ///< bytes from the start of a point
  PointFieldType datatype = PointFieldType::kFloat32;
  uint32_t count = 1;  ///< elements of `datatype`
};

/// sensor_msgs/PointCloud2: `height` rows of `width` points, each `point_step` bytes laid out
/// as `fields` say; `data` holds height × row_step bytes. point_cloud.h builds and reads the
/// x, y, z (float32) layout swlio publishes.
struct PointCloud2 {
  int64_t t_ns = 0;
  std::string frame_id;
  uint32_t height = 1;
  uint32_t width = 0;
  std::vector<PointField> fields;
  bool is_bigendian = false;
  uint32_t point_step = 0;  ///< bytes per point
  uint32_t row_step = 0;    ///< bytes per row (width × point_step when rows are packed)
  std::vector<uint8_t> data;
  bool is_dense = true;  ///< no invalid (NaN) points
};

/// A received sample with the times it was written and taken.
template <typename Message>
struct Received {
  Message msg;
  int64_t receive_steady_ns = 0;    ///< CLOCK_MONOTONIC when the reader took it
  int64_t receive_realtime_ns = 0;  ///< CLOCK_REALTIME when the reader took it
  int64_t source_realtime_ns = 0;   ///< writer's CLOCK_REALTIME at dds_write (DDS source time)
};

/// "pose", "odometry", "health", "path", "map", "odom_odometry", "tf" or "tf_static".
const char* TopicLabel(Topic topic);

}  // namespace swlio::ipc
