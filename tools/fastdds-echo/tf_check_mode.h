#pragma once
/// @file
/// The `--tf-check` mode of swlio-fastdds-echo: subscribes as a ROS 2 node with a tf2 listener
/// does — /tf (tf2's listener QoS: RELIABLE, VOLATILE, KEEP_LAST 100), /tf_static (RELIABLE,
/// TRANSIENT_LOCAL, KEEP_LAST 1, as tf2_ros's static listener) and the map-frame pose (ROS 2's
/// default subscription) — and prints what TfCheck (tf_check.h) finds for every pose.

#include <fastdds/dds/domain/DomainParticipant.hpp>

#include <string>

#include "tf_check.h"

namespace swlio::tools::fastdds_echo {

struct TfCheckOptions {
  std::string pose_topic = "rt/swlio/pose";
  std::string tf_topic = "rt/tf";
  std::string tf_static_topic = "rt/tf_static";
  TfCheckFrames frames;
  double duration_s = 30.0;  ///< runs this long, then reports the poses still waiting
};

/// Runs the check on `participant` for `options.duration_s`; the exit code (0, or 1 when a
/// reader cannot be created).
int RunTfCheck(eprosima::fastdds::dds::DomainParticipant* participant,
               const TfCheckOptions& options);

}  // namespace swlio::tools::fastdds_echo
