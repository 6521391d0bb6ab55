#pragma once
/// @file
/// Private to ipc/: conversions between the C++ messages (messages.h) and the idlc-generated C
/// structs (ipc/idl/*.idl), plus the per-topic DDS plumbing shared by writers and readers.
///
/// Outgoing conversions borrow: strings and sequences of the C struct point into the C++
/// message (no copy), so the C struct is valid only while the message is alive and unchanged.

#include <dds/dds.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "diagnostic_msgs.h"
#include "geometry_msgs.h"
#include "nav_msgs.h"
#include "sensor_msgs.h"
#include "swlio/ipc/ipc_config.h"
#include "swlio/ipc/messages.h"
#include "tf2_msgs.h"

namespace swlio::ipc::wire {

using TimeMsg = builtin_interfaces_msg_dds__Time_;
using HeaderMsg = std_msgs_msg_dds__Header_;
using PoseMsg = geometry_msgs_msg_dds__Pose_;
using PoseStampedMsg = geometry_msgs_msg_dds__PoseStamped_;
using PoseCovStampedMsg = geometry_msgs_msg_dds__PoseWithCovarianceStamped_;
using TwistMsg = geometry_msgs_msg_dds__Twist_;
using OdometryMsg = nav_msgs_msg_dds__Odometry_;
using PathMsg = nav_msgs_msg_dds__Path_;
using KeyValueMsg = diagnostic_msgs_msg_dds__KeyValue_;
using StatusMsg = diagnostic_msgs_msg_dds__DiagnosticStatus_;
using DiagnosticArrayMsg = diagnostic_msgs_msg_dds__DiagnosticArray_;
using PointFieldMsg = sensor_msgs_msg_dds__PointField_;
using PointCloud2Msg = sensor_msgs_msg_dds__PointCloud2_;
using TransformStampedMsg = geometry_msgs_msg_dds__TransformStamped_;
using TFMessageMsg = tf2_msgs_msg_dds__TFMessage_;

/// int64 ns ↔ builtin_interfaces/Time (sec = floor(t_ns / 1e9)). ToTime fails when the
/// seconds do not fit an int32; FromTime fails when nanosec ≥ 1e9.
bool ToTime(int64_t t_ns, TimeMsg* out);
bool FromTime(const TimeMsg& time, int64_t* t_ns);

bool ToHeader(int64_t t_ns, const std::string& frame_id, HeaderMsg* out);
bool FromHeader(const HeaderMsg& header, int64_t* t_ns, std::string* frame_id);

void ToPose(const Pose& pose, PoseMsg* out);
Pose FromPose(const PoseMsg& pose);
void ToTwist(const Twist& twist, TwistMsg* out);
Twist FromTwist(const TwistMsg& twist);

bool ToWire(const PoseWithCovarianceStamped& in, PoseCovStampedMsg* out);
bool FromWire(const PoseCovStampedMsg& in, PoseWithCovarianceStamped* out);
bool ToWire(const Odometry& in, OdometryMsg* out);
bool FromWire(const OdometryMsg& in, Odometry* out);

/// Storage the borrowed C structs of a Path point into.
struct PathStorage {
  std::vector<PoseStampedMsg> poses;
};
bool ToWire(const Path& in, PathStorage* storage, PathMsg* out);
bool FromWire(const PathMsg& in, Path* out);

/// Storage the borrowed C structs of a DiagnosticArray point into.
struct DiagnosticStorage {
  std::vector<StatusMsg> status;
  std::vector<std::vector<KeyValueMsg>> values;
};
bool ToWire(const DiagnosticArray& in, DiagnosticStorage* storage, DiagnosticArrayMsg* out);
bool FromWire(const DiagnosticArrayMsg& in, DiagnosticArray* out);

/// Storage the borrowed C structs of a PointCloud2 point into (the data bytes are borrowed from
/// the message itself, not copied).
struct PointCloudStorage {
  std::vector<PointFieldMsg> fields;
};
bool ToWire(const PointCloud2& in, PointCloudStorage* storage, PointCloud2Msg* out);
bool FromWire(const PointCloud2Msg& in, PointCloud2* out);

/// Storage the borrowed C structs of a TFMessage point into: up to kInline transforms (what
/// swliod sends at IMU rate) without allocating.
struct TfStorage {
  static constexpr size_t kInline = 4;
  std::array<TransformStampedMsg, kInline> inline_transforms{};
  std::vector<TransformStampedMsg> more;
};
bool ToWire(const TFMessage& in, TfStorage* storage, TFMessageMsg* out);
bool FromWire(const TFMessageMsg& in, TFMessage* out);

/// The generated type descriptor of `topic`'s message.
const dds_topic_descriptor_t* Descriptor(Topic topic);
/// "rt/" + the topic's ROS 2 name from `config`.
std::string DdsTopicName(const IpcConfig& config, Topic topic);
/// QoS for `topic` (qos_profile.h); readers use `reader_depth` for KEEP_LAST. Caller frees.
dds_qos_t* MakeQos(Topic topic, bool writer, int reader_depth);

}  // namespace swlio::ipc::wire
