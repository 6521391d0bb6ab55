#pragma once
/// @file
/// Which bag topics feed which swlio input, found by message type.
///
/// Roles and the kinds that fill them (message_decoder.h): LiDAR — the packet kinds and
/// PointCloud2; IMU — Imu; GNSS — NavSatFix; wheel — Odometry, TwistStamped. A role takes the
/// topic the caller names (`--lidar-topic` …: it must exist and carry a type of the role), else
/// the only topic of such a type; several candidates are an error that lists them and names
/// the option to choose with. rslidar_sdk publishes DIFOP packets on `<packets topic>_difop`
/// (washing_house: /rslidar_packets + /rslidar_packets_difop): such a topic is never a LiDAR
/// candidate of its own, and joins the chosen LiDAR topic as its calibration source.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/bag/ros_messages.h"

namespace swlio::drivers::bag {

enum class TopicRole : uint8_t { kLidar, kImu, kGnss, kWheel, kNone };

/// The role a message kind can fill.
TopicRole RoleOf(RosMessageKind kind);
const char* RoleName(TopicRole role);

/// Topic names the caller chose; empty: find by type.
struct TopicChoice {
  std::string lidar;
  std::string imu;
  std::string gnss;
  std::string wheel;
};

/// Topic indices (into BagReader::topics()) per role; unset when the bag has none.
struct SelectedTopics {
  std::optional<uint32_t> lidar;
  std::optional<uint32_t> lidar_info;  ///< `<lidar>_difop`, when present
  std::optional<uint32_t> imu;
  std::optional<uint32_t> gnss;
  std::optional<uint32_t> wheel;
};

/// Chooses per role. False with `error` when a named topic is missing or of another role, or
/// several topics fit a role nobody named.
bool SelectTopics(const std::vector<BagTopic>& topics,
                  const TopicChoice& choice,
                  SelectedTopics* out,
                  std::string* error);

}  // namespace swlio::drivers::bag
