#pragma once
/// @file
/// Text forms of received swlio samples for swlio-echo: one human line per sample, TUM
/// trajectory lines and latency CSV rows. Every double is printed in its shortest form that
/// reads back to the same bits (std::to_chars), stamps as exact "sec.nanosec".

#include <cstdint>
#include <string>

#include "swlio/ipc/messages.h"

namespace swlio::tools::echo {

/// t_ns as exact decimal seconds with nine decimals ("-0.000000001" for -1).
std::string FormatStamp(int64_t t_ns);
/// Shortest round-trip decimal form of `v` ("nan", "inf", "-0" included).
std::string FormatDouble(double v);

std::string FormatLine(const ipc::PoseWithCovarianceStamped& m);
std::string FormatLine(const ipc::Odometry& m);
std::string FormatLine(const ipc::DiagnosticArray& m);
std::string FormatLine(const ipc::Path& m);
/// "tf n=N | parent -> child t=... p=[x y z] q=[x y z w] | ..." (/tf and /tf_static).
std::string FormatLine(const ipc::TFMessage& m);
/// A summary, never the points: "map t=... frame=... points=N (width×height) bytes=B
/// point_step=S fields=x,y,z" plus, for the x/y/z float32 layout, the points' bounding box
/// "min=[...] max=[...]".
std::string FormatLine(const ipc::PointCloud2& m);

/// "t x y z qx qy qz qw" (TUM RGB-D benchmark trajectory format).
std::string TumLine(int64_t t_ns, const ipc::Pose& pose);
inline constexpr const char* kTumHeader = "# timestamp tx ty tz qx qy qz qw";

/// A sample's header stamp; a TFMessage's is its first transform's (0 when empty).
template <typename Message>
int64_t StampNs(const Message& m) {
  return m.t_ns;
}
inline int64_t StampNs(const ipc::TFMessage& m) {
  return m.transforms.empty() ? 0 : m.transforms.front().t_ns;
}

/// The stamp's age when taken, on the clock it is on: swliod stamps on CLOCK_REALTIME or
/// CLOCK_MONOTONIC (ipc.stamp_clock), and a stamp is far nearer its own clock's receive time
/// than the other's (decades apart), so the nearer one is taken.
template <typename Message>
int64_t StampAgeNs(const ipc::Received<Message>& r) {
  const int64_t steady_ns = r.receive_steady_ns - StampNs(r.msg);
  const int64_t realtime_ns = r.receive_realtime_ns - StampNs(r.msg);
  return (steady_ns < 0 ? -steady_ns : steady_ns) <= (realtime_ns < 0 ? -realtime_ns : realtime_ns)
             ? steady_ns
             : realtime_ns;
}

/// Latency CSV: the stamp, the writer's source time, the receive times, and two differences:
/// transport_ns = receive_realtime − source_realtime (write → take, same host), and
/// age_ns = StampAgeNs (end-to-end: the receive time on the stamp's clock − the stamp).
inline constexpr const char* kLatencyHeader =
    "topic,stamp_ns,source_realtime_ns,receive_realtime_ns,receive_steady_ns,transport_ns,age_ns";
template <typename Message>
std::string LatencyRow(ipc::Topic topic, const ipc::Received<Message>& r) {
  std::string out = ipc::TopicLabel(topic);
  for (const int64_t v :
       {StampNs(r.msg), r.source_realtime_ns, r.receive_realtime_ns, r.receive_steady_ns,
        r.receive_realtime_ns - r.source_realtime_ns, StampAgeNs(r)}) {
    out.append(",").append(std::to_string(v));
  }
  return out;
}

}  // namespace swlio::tools::echo
