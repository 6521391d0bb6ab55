// sensor_msgs/PointCloud2 as stored (message_decoder.h). Fields (common_interfaces humble
// 53761cb sensor_msgs/msg/PointCloud2.msg, PointField.msg): Header header; uint32 height;
// uint32 width; PointField[] fields {string name; uint32 offset; uint8 datatype; uint32 count};
// bool is_bigendian; uint32 point_step; uint32 row_step; uint8[] data; bool is_dense.
// Whether the fields and sizes agree is point_cloud_points.h's check, not the wire format's.

#include "swlio/drivers/bag/message_decoder.h"

namespace swlio::drivers::bag {
namespace {

// Smallest PointField on the wire: name length (4, its NUL in CDR counted in the string),
// offset 4, datatype 1, count 4.
constexpr size_t kMinPointFieldBytes = 13;

}  // namespace

bool DecodePointCloud2(MessageReader& r, PointCloud2Msg* out) {
  out->header = r.Header();
  out->height = r.U32("height");
  out->width = r.U32("width");
  out->fields.clear();
  const uint32_t n = r.SequenceLength("fields", kMinPointFieldBytes);
  for (uint32_t i = 0; i < n && r.ok(); ++i) {
    PointFieldView f;
    f.name = r.String("fields[].name");
    f.offset = r.U32("fields[].offset");
    f.datatype = r.U8("fields[].datatype");
    f.count = r.U32("fields[].count");
    out->fields.push_back(f);
  }
  out->is_bigendian = r.U8("is_bigendian") != 0;
  out->point_step = r.U32("point_step");
  out->row_step = r.U32("row_step");
  const uint32_t bytes = r.SequenceLength("data", 1);
  out->data = r.Bytes(bytes, "data");
  out->is_dense = r.U8("is_dense") != 0;
  return r.Finish();
}

}  // namespace swlio::drivers::bag
