// ros2msg schema texts (ros2msg_schema.h).

#include "swlio/drivers/bag/ros2msg_schema.h"

#include <map>
#include <set>
#include <sstream>

#include "swlio/drivers/bag/message_decoder.h"

namespace swlio::drivers::bag {
namespace {

/// Fields and constants per type, one per line, as the .msg files of ROS 2 Jazzy declare them
/// (common_interfaces: sensor_msgs/msg/{PointCloud2,PointField,Imu,NavSatFix,NavSatStatus}.msg,
/// std_msgs/msg/Header.msg, geometry_msgs/msg/*.msg, nav_msgs/msg/Odometry.msg;
/// rcl_interfaces: builtin_interfaces/msg/Time.msg; geometry2: tf2_msgs/msg/TFMessage.msg).
const std::map<std::string, std::string, std::less<>>& Definitions() {
  static const std::map<std::string, std::string, std::less<>> defs = {
      {"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"},
      {"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
      {"sensor_msgs/PointField",
       "uint8 INT8 = 1\nuint8 UINT8 = 2\nuint8 INT16 = 3\nuint8 UINT16 = 4\nuint8 INT32 = 5\n"
       "uint8 UINT32 = 6\nuint8 FLOAT32 = 7\nuint8 FLOAT64 = 8\n"
       "string name\nuint32 offset\nuint8 datatype\nuint32 count\n"},
      {"sensor_msgs/PointCloud2",
       "std_msgs/Header header\nuint32 height\nuint32 width\nPointField[] fields\n"
       "bool is_bigendian\nuint32 point_step\nuint32 row_step\nuint8[] data\nbool is_dense\n"},
      {"geometry_msgs/Quaternion", "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n"},
      {"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/Pose", "Point position\nQuaternion orientation\n"},
      {"geometry_msgs/PoseWithCovariance", "Pose pose\nfloat64[36] covariance\n"},
      {"geometry_msgs/Twist", "Vector3 linear\nVector3 angular\n"},
      {"geometry_msgs/TwistWithCovariance", "Twist twist\nfloat64[36] covariance\n"},
      {"geometry_msgs/TwistStamped", "std_msgs/Header header\nTwist twist\n"},
      {"geometry_msgs/Transform", "Vector3 translation\nQuaternion rotation\n"},
      {"geometry_msgs/TransformStamped",
       "std_msgs/Header header\nstring child_frame_id\nTransform transform\n"},
      {"tf2_msgs/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
      {"sensor_msgs/Imu",
       "std_msgs/Header header\ngeometry_msgs/Quaternion orientation\n"
       "float64[9] orientation_covariance\ngeometry_msgs/Vector3 angular_velocity\n"
       "float64[9] angular_velocity_covariance\ngeometry_msgs/Vector3 linear_acceleration\n"
       "float64[9] linear_acceleration_covariance\n"},
      {"sensor_msgs/NavSatStatus",
       "int8 STATUS_UNKNOWN = -2\nint8 STATUS_NO_FIX = -1\nint8 STATUS_FIX = 0\n"
       "int8 STATUS_SBAS_FIX = 1\nint8 STATUS_GBAS_FIX = 2\nint8 status -2\n"
       "uint16 SERVICE_UNKNOWN = 0\nuint16 SERVICE_GPS = 1\nuint16 SERVICE_GLONASS = 2\n"
       "uint16 SERVICE_COMPASS = 4\nuint16 SERVICE_GALILEO = 8\nuint16 service\n"},
      {"sensor_msgs/NavSatFix",
       "std_msgs/Header header\nNavSatStatus status\nfloat64 latitude\nfloat64 longitude\n"
       "float64 altitude\nfloat64[9] position_covariance\n"
       "uint8 COVARIANCE_TYPE_UNKNOWN = 0\nuint8 COVARIANCE_TYPE_APPROXIMATED = 1\n"
       "uint8 COVARIANCE_TYPE_DIAGONAL_KNOWN = 2\nuint8 COVARIANCE_TYPE_KNOWN = 3\n"
       "uint8 position_covariance_type\n"},
      {"nav_msgs/Odometry",
       "std_msgs/Header header\nstring child_frame_id\n"
       "geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n"},
  };
  return defs;
}

bool IsPrimitive(const std::string& t) {
  static const std::set<std::string> p = {"bool",   "byte",  "char",   "float32", "float64",
                                          "int8",   "uint8", "int16",  "uint16",  "int32",
                                          "uint32", "int64", "uint64", "string"};
  return p.count(t) > 0;
}

/// The message types `text` (a definition of a type in `package`) uses, as "pkg/Type", sorted.
std::set<std::string> Dependencies(const std::string& text, const std::string& package) {
  std::set<std::string> out;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::string type = line.substr(0, line.find(' '));
    type = type.substr(0, type.find('['));
    if (type.empty() || IsPrimitive(type)) continue;
    if (type.find('/') == std::string::npos) type.insert(0, package + "/");
    out.insert(type);
  }
  return out;
}

void Append(const std::string& type, std::set<std::string>* seen, std::string* out) {
  const std::string& text = Definitions().find(type)->second;
  *out += text;
  for (const std::string& dep : Dependencies(text, type.substr(0, type.find('/')))) {
    if (!seen->insert(dep).second) continue;
    *out += "\n" + std::string(80, '=') + "\nMSG: " + dep + "\n";
    Append(dep, seen, out);
  }
}

}  // namespace

std::string Ros2MsgSchema(std::string_view type) {
  const std::string name = NormalizeTypeName(type);
  if (Definitions().find(name) == Definitions().end()) return {};
  std::set<std::string> seen;
  std::string out;
  Append(name, &seen, &out);
  return out;
}

}  // namespace swlio::drivers::bag
