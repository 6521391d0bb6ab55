// sensor_msgs/Imu, sensor_msgs/NavSatFix, nav_msgs/Odometry and geometry_msgs/TwistStamped
// (message_decoder.h). Field order as in ros2/common_interfaces humble 53761cb and jazzy
// 5283bd9 (identical wire layout in both and in ROS 1 noetic common_msgs 20a833b):
//   Imu: Header; Quaternion orientation; float64[9] cov; Vector3 angular_velocity; float64[9];
//        Vector3 linear_acceleration; float64[9]
//   NavSatFix: Header; NavSatStatus {int8 status; uint16 service}; float64 latitude,
//        longitude, altitude; float64[9] position_covariance; uint8 position_covariance_type
//   Odometry: Header; string child_frame_id; PoseWithCovariance {Pose {Point; Quaternion};
//        float64[36]}; TwistWithCovariance {Twist {Vector3 linear; Vector3 angular}; float64[36]}
//   TwistStamped: Header; Twist
// Quaternion is x, y, z, w; Point and Vector3 are x, y, z; all float64.

#include "swlio/drivers/bag/message_decoder.h"

namespace swlio::drivers::bag {
namespace {

Eigen::Vector3d Vector3(MessageReader& r, const char* what) {
  const double x = r.F64(what);
  const double y = r.F64(what);
  const double z = r.F64(what);
  return {x, y, z};
}

Eigen::Quaterniond Quaternion(MessageReader& r, const char* what) {
  const double x = r.F64(what);
  const double y = r.F64(what);
  const double z = r.F64(what);
  const double w = r.F64(what);
  return {w, x, y, z};  // Eigen's constructor takes w first
}

}  // namespace

bool DecodeImu(MessageReader& r, ImuMsg* out) {
  out->header = r.Header();
  out->orientation = Quaternion(r, "orientation");
  r.F64Array(out->orientation_covariance.data(), 9, "orientation_covariance");
  out->angular_velocity_radps = Vector3(r, "angular_velocity");
  r.F64Array(out->angular_velocity_covariance.data(), 9, "angular_velocity_covariance");
  out->linear_acceleration_mps2 = Vector3(r, "linear_acceleration");
  r.F64Array(out->linear_acceleration_covariance.data(), 9, "linear_acceleration_covariance");
  return r.Finish();
}

bool DecodeNavSatFix(MessageReader& r, NavSatFixMsg* out) {
  out->header = r.Header();
  out->status = r.I8("status.status");
  out->service = r.U16("status.service");
  out->latitude_deg = r.F64("latitude");
  out->longitude_deg = r.F64("longitude");
  out->altitude_m = r.F64("altitude");
  r.F64Array(out->position_covariance_m2.data(), 9, "position_covariance");
  out->position_covariance_type = r.U8("position_covariance_type");
  return r.Finish();
}

bool DecodeOdometry(MessageReader& r, OdometryMsg* out) {
  out->header = r.Header();
  out->child_frame_id = r.String("child_frame_id");
  out->position_m = Vector3(r, "pose.pose.position");
  out->orientation = Quaternion(r, "pose.pose.orientation");
  r.F64Array(out->pose_covariance.data(), 36, "pose.covariance");
  out->linear_velocity_mps = Vector3(r, "twist.twist.linear");
  out->angular_velocity_radps = Vector3(r, "twist.twist.angular");
  r.F64Array(out->twist_covariance.data(), 36, "twist.covariance");
  return r.Finish();
}

bool DecodeTwistStamped(MessageReader& r, TwistStampedMsg* out) {
  out->header = r.Header();
  out->linear_velocity_mps = Vector3(r, "twist.linear");
  out->angular_velocity_radps = Vector3(r, "twist.angular");
  return r.Finish();
}

}  // namespace swlio::drivers::bag
