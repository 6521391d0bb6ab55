#pragma once
/// @file
/// `--initialpose X,Y,YAW_DEG@AFTER_S` of swlio-fastdds-echo: publishes
/// geometry_msgs/PoseWithCovarianceStamped on /initialpose as rviz2's "2D Pose Estimate" does
/// (frame "map", x/y variance 0.25, yaw variance 0.0685; stamped on CLOCK_REALTIME; writer
/// RELIABLE, VOLATILE, KEEP_LAST 10 as an rclcpp publisher with the default QoS), AFTER_S
/// seconds after the program started, once a reader has matched. Prints one line per message:
/// "initialpose x=… y=… yaw_deg=… sent_mono_ns=…" (CLOCK_MONOTONIC, for the test's timing).

#include <fastdds/dds/domain/DomainParticipant.hpp>

#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace swlio::tools::fastdds_echo {

struct InitialPoseSend {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_deg = 0.0;
  double after_s = 0.0;
};

/// "X,Y,YAW_DEG@AFTER_S"; std::nullopt when it does not parse.
std::optional<InitialPoseSend> ParseInitialPose(const std::string& text);

/// Sends each on its own thread; the destructor waits for the thread.
class InitialPoseWriter {
 public:
  /// Null when Fast DDS refuses the writer.
  static std::unique_ptr<InitialPoseWriter> Create(
      eprosima::fastdds::dds::DomainParticipant* participant,
      const std::string& topic,
      std::vector<InitialPoseSend> sends);
  ~InitialPoseWriter();

 private:
  InitialPoseWriter() = default;
  std::thread thread_;
};

}  // namespace swlio::tools::fastdds_echo
