#include "wire.h"

#include <algorithm>
#include <limits>

#include "swlio/core/time.h"
#include "swlio/ipc/qos_profile.h"

namespace swlio::ipc::wire {
namespace {

/// Borrowed pointer for a generated `char*` field; Cyclone only reads it on write.
char* Borrow(const std::string& s) { return const_cast<char*>(s.c_str()); }

std::string Copy(const char* s) { return s == nullptr ? std::string() : std::string(s); }

void ToCovariance(const Covariance6& in, double* out) { std::copy(in.begin(), in.end(), out); }

Covariance6 FromCovariance(const double* in) {
  Covariance6 out;
  std::copy(in, in + out.size(), out.begin());
  return out;
}

template <typename Seq, typename Element>
void BorrowSequence(std::vector<Element>& elements, Seq* seq) {
  seq->_length = static_cast<uint32_t>(elements.size());
  seq->_maximum = seq->_length;
  seq->_buffer = elements.empty() ? nullptr : elements.data();
  seq->_release = false;
}

}  // namespace

bool ToTime(int64_t t_ns, TimeMsg* out) {
  int64_t sec = t_ns / kNsPerSec;
  int64_t nanosec = t_ns % kNsPerSec;
  if (nanosec < 0) {
    nanosec += kNsPerSec;
    --sec;
  }
  if (sec < std::numeric_limits<int32_t>::min() || sec > std::numeric_limits<int32_t>::max()) {
    return false;
  }
  out->sec = static_cast<int32_t>(sec);
  out->nanosec = static_cast<uint32_t>(nanosec);
  return true;
}

bool FromTime(const TimeMsg& time, int64_t* t_ns) {
  if (time.nanosec >= static_cast<uint32_t>(kNsPerSec)) return false;
  *t_ns = static_cast<int64_t>(time.sec) * kNsPerSec + static_cast<int64_t>(time.nanosec);
  return true;
}

bool ToHeader(int64_t t_ns, const std::string& frame_id, HeaderMsg* out) {
  out->frame_id = Borrow(frame_id);
  return ToTime(t_ns, &out->stamp);
}

bool FromHeader(const HeaderMsg& header, int64_t* t_ns, std::string* frame_id) {
  *frame_id = Copy(header.frame_id);
  return FromTime(header.stamp, t_ns);
}

void ToPose(const Pose& pose, PoseMsg* out) {
  out->position = {pose.position_m[0], pose.position_m[1], pose.position_m[2]};
  const auto& q = pose.orientation_xyzw;
  out->orientation = {q[0], q[1], q[2], q[3]};
}

Pose FromPose(const PoseMsg& pose) {
  Pose out;
  out.position_m = {pose.position.x, pose.position.y, pose.position.z};
  const auto& q = pose.orientation;
  out.orientation_xyzw = {q.x, q.y, q.z, q.w};
  return out;
}

void ToTwist(const Twist& twist, TwistMsg* out) {
  out->linear = {twist.linear_mps[0], twist.linear_mps[1], twist.linear_mps[2]};
  out->angular = {twist.angular_radps[0], twist.angular_radps[1], twist.angular_radps[2]};
}

Twist FromTwist(const TwistMsg& twist) {
  Twist out;
  out.linear_mps = {twist.linear.x, twist.linear.y, twist.linear.z};
  out.angular_radps = {twist.angular.x, twist.angular.y, twist.angular.z};
  return out;
}

bool ToWire(const PoseWithCovarianceStamped& in, PoseCovStampedMsg* out) {
  ToPose(in.pose, &out->pose.pose);
  ToCovariance(in.covariance, out->pose.covariance);
  return ToHeader(in.t_ns, in.frame_id, &out->header);
}

bool FromWire(const PoseCovStampedMsg& in, PoseWithCovarianceStamped* out) {
  out->pose = FromPose(in.pose.pose);
  out->covariance = FromCovariance(in.pose.covariance);
  return FromHeader(in.header, &out->t_ns, &out->frame_id);
}

bool ToWire(const Odometry& in, OdometryMsg* out) {
  out->child_frame_id = Borrow(in.child_frame_id);
  ToPose(in.pose, &out->pose.pose);
  ToCovariance(in.pose_covariance, out->pose.covariance);
  ToTwist(in.twist, &out->twist.twist);
  ToCovariance(in.twist_covariance, out->twist.covariance);
  return ToHeader(in.t_ns, in.frame_id, &out->header);
}

bool FromWire(const OdometryMsg& in, Odometry* out) {
  out->child_frame_id = Copy(in.child_frame_id);
  out->pose = FromPose(in.pose.pose);
  out->pose_covariance = FromCovariance(in.pose.covariance);
  out->twist = FromTwist(in.twist.twist);
  out->twist_covariance = FromCovariance(in.twist.covariance);
  return FromHeader(in.header, &out->t_ns, &out->frame_id);
}

bool ToWire(const Path& in, PathStorage* storage, PathMsg* out) {
  storage->poses.resize(in.poses.size());
  for (size_t i = 0; i < in.poses.size(); ++i) {
    ToPose(in.poses[i].pose, &storage->poses[i].pose);
    if (!ToHeader(in.poses[i].t_ns, in.poses[i].frame_id, &storage->poses[i].header)) return false;
  }
  BorrowSequence(storage->poses, &out->poses);
  return ToHeader(in.t_ns, in.frame_id, &out->header);
}

bool FromWire(const PathMsg& in, Path* out) {
  out->poses.resize(in.poses._length);
  for (uint32_t i = 0; i < in.poses._length; ++i) {
    const PoseStampedMsg& p = in.poses._buffer[i];
    out->poses[i].pose = FromPose(p.pose);
    if (!FromHeader(p.header, &out->poses[i].t_ns, &out->poses[i].frame_id)) return false;
  }
  return FromHeader(in.header, &out->t_ns, &out->frame_id);
}

bool ToWire(const DiagnosticArray& in, DiagnosticStorage* storage, DiagnosticArrayMsg* out) {
  storage->status.resize(in.status.size());
  storage->values.resize(in.status.size());
  for (size_t i = 0; i < in.status.size(); ++i) {
    const DiagnosticStatus& s = in.status[i];
    StatusMsg& m = storage->status[i];
    m.level = static_cast<uint8_t>(s.level);
    m.name = Borrow(s.name);
    m.message = Borrow(s.message);
    m.hardware_id = Borrow(s.hardware_id);
    std::vector<KeyValueMsg>& kv = storage->values[i];
    kv.resize(s.values.size());
    for (size_t j = 0; j < s.values.size(); ++j) {
      kv[j].key = Borrow(s.values[j].key);
      kv[j].value = Borrow(s.values[j].value);
    }
    BorrowSequence(kv, &m.values);
  }
  BorrowSequence(storage->status, &out->status);
  return ToHeader(in.t_ns, in.frame_id, &out->header);
}

bool FromWire(const DiagnosticArrayMsg& in, DiagnosticArray* out) {
  out->status.resize(in.status._length);
  for (uint32_t i = 0; i < in.status._length; ++i) {
    const StatusMsg& m = in.status._buffer[i];
    DiagnosticStatus& s = out->status[i];
    s.level = static_cast<DiagnosticLevel>(m.level);
    s.name = Copy(m.name);
    s.message = Copy(m.message);
    s.hardware_id = Copy(m.hardware_id);
    s.values.resize(m.values._length);
    for (uint32_t j = 0; j < m.values._length; ++j) {
      s.values[j] = {Copy(m.values._buffer[j].key), Copy(m.values._buffer[j].value)};
    }
  }
  return FromHeader(in.header, &out->t_ns, &out->frame_id);
}

bool ToWire(const PointCloud2& in, PointCloudStorage* storage, PointCloud2Msg* out) {
  if (in.data.size() > std::numeric_limits<uint32_t>::max()) return false;
  storage->fields.resize(in.fields.size());
  for (size_t i = 0; i < in.fields.size(); ++i) {
    const PointField& f = in.fields[i];
    storage->fields[i] = {Borrow(f.name), f.offset, static_cast<uint8_t>(f.datatype), f.count};
  }
  BorrowSequence(storage->fields, &out->fields);
  out->height = in.height;
  out->width = in.width;
  out->is_bigendian = in.is_bigendian;
  out->point_step = in.point_step;
  out->row_step = in.row_step;
  // Borrowed like the strings: Cyclone only reads the buffer while it serializes the sample.
  out->data._length = static_cast<uint32_t>(in.data.size());
  out->data._maximum = out->data._length;
  out->data._buffer = const_cast<uint8_t*>(in.data.empty() ? nullptr : in.data.data());
  out->data._release = false;
  out->is_dense = in.is_dense;
  return ToHeader(in.t_ns, in.frame_id, &out->header);
}

bool FromWire(const PointCloud2Msg& in, PointCloud2* out) {
  out->fields.resize(in.fields._length);
  for (uint32_t i = 0; i < in.fields._length; ++i) {
    const PointFieldMsg& f = in.fields._buffer[i];
    out->fields[i] = {Copy(f.name), f.offset, static_cast<PointFieldType>(f.datatype), f.count};
  }
  out->height = in.height;
  out->width = in.width;
  out->is_bigendian = in.is_bigendian;
  out->point_step = in.point_step;
  out->row_step = in.row_step;
  out->data.assign(in.data._buffer, in.data._buffer + in.data._length);
  out->is_dense = in.is_dense;
  return FromHeader(in.header, &out->t_ns, &out->frame_id);
}

namespace {

bool ToWire(const TransformStamped& in, TransformStampedMsg* out) {
  out->child_frame_id = Borrow(in.child_frame_id);
  const auto& t = in.transform.translation_m;
  const auto& q = in.transform.rotation_xyzw;
  out->transform.translation = {t[0], t[1], t[2]};
  out->transform.rotation = {q[0], q[1], q[2], q[3]};
  return ToHeader(in.t_ns, in.frame_id, &out->header);
}

}  // namespace

bool ToWire(const TFMessage& in, TfStorage* storage, TFMessageMsg* out) {
  const size_t n = in.transforms.size();
  TransformStampedMsg* buffer = storage->inline_transforms.data();
  if (n > TfStorage::kInline) {
    storage->more.resize(n);
    buffer = storage->more.data();
  }
  for (size_t i = 0; i < n; ++i) {
    if (!ToWire(in.transforms[i], &buffer[i])) return false;
  }
  out->transforms._length = static_cast<uint32_t>(n);
  out->transforms._maximum = out->transforms._length;
  out->transforms._buffer = n == 0 ? nullptr : buffer;
  out->transforms._release = false;
  return true;
}

bool FromWire(const TFMessageMsg& in, TFMessage* out) {
  out->transforms.resize(in.transforms._length);
  for (uint32_t i = 0; i < in.transforms._length; ++i) {
    const TransformStampedMsg& m = in.transforms._buffer[i];
    TransformStamped& t = out->transforms[i];
    t.child_frame_id = Copy(m.child_frame_id);
    t.transform.translation_m = {m.transform.translation.x, m.transform.translation.y,
                                 m.transform.translation.z};
    const auto& q = m.transform.rotation;
    t.transform.rotation_xyzw = {q.x, q.y, q.z, q.w};
    if (!FromHeader(m.header, &t.t_ns, &t.frame_id)) return false;
  }
  return true;
}

const dds_topic_descriptor_t* Descriptor(Topic topic) {
  switch (topic) {
    case Topic::kPose:
      return &geometry_msgs_msg_dds__PoseWithCovarianceStamped__desc;
    case Topic::kOdometry:
      return &nav_msgs_msg_dds__Odometry__desc;
    case Topic::kHealth:
      return &diagnostic_msgs_msg_dds__DiagnosticArray__desc;
    case Topic::kPath:
      return &nav_msgs_msg_dds__Path__desc;
    case Topic::kMap:
    case Topic::kSweep:
      return &sensor_msgs_msg_dds__PointCloud2__desc;
    case Topic::kOdomOdometry:
      return &nav_msgs_msg_dds__Odometry__desc;
    case Topic::kTf:
    case Topic::kTfStatic:
      return &tf2_msgs_msg_dds__TFMessage__desc;
  }
  return nullptr;
}

std::string DdsTopicName(const IpcConfig& config, Topic topic) {
  switch (topic) {
    case Topic::kPose:
      return "rt/" + config.pose_topic;
    case Topic::kOdometry:
      return "rt/" + config.odometry_topic;
    case Topic::kHealth:
      return "rt/" + config.health_topic;
    case Topic::kPath:
      return "rt/" + config.path_topic;
    case Topic::kMap:
      return "rt/" + config.map_topic;
    case Topic::kOdomOdometry:
      return "rt/" + config.odom_odometry_topic;
    case Topic::kTf:
      return "rt/" + config.tf_topic;
    case Topic::kTfStatic:
      return "rt/" + config.tf_static_topic;
    case Topic::kSweep:
      return config.sweep_topic.empty() ? std::string() : "rt/" + config.sweep_topic;
  }
  return {};
}

dds_qos_t* MakeQos(Topic topic, bool writer, int reader_depth) {
  const QosProfile profile = WriterQos(topic);
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos,
                       profile.reliability == Reliability::kReliable ? DDS_RELIABILITY_RELIABLE
                                                                     : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_MSECS(100));
  dds_qset_durability(qos, profile.durability == Durability::kTransientLocal
                               ? DDS_DURABILITY_TRANSIENT_LOCAL
                               : DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, writer ? profile.depth : reader_depth);
  if (writer) {
    const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
    dds_qset_data_representation(qos, 1, &xcdr1);
  }
  return qos;
}

}  // namespace swlio::ipc::wire
