#pragma once
/// @file
/// Writes swlio's topics on a Participant. Cyclone DDS stays behind this header.
///
/// Topic names are IpcConfig's ROS 2 names with the "rt/" prefix ROS 2 uses for topics
/// ("swlio/pose" → DDS "rt/swlio/pose"). QoS follows ROS 2 conventions (see qos_profile.h and
/// ipc/README.md): every writer is RELIABLE and KEEP_LAST, so it never blocks the caller and
/// matches both reliable and best-effort readers; the path, the map and /tf_static are
/// TRANSIENT_LOCAL (latched).
/// Writers pin XCDR1, the encoding Fast DDS 2.9 (ROS 2's default middleware) reads.
///
/// Thread safety: each Publish* may be called from any one thread at a time per topic; the
/// methods share no mutable state except the atomic counters.

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "swlio/ipc/ipc_config.h"
#include "swlio/ipc/messages.h"
#include "swlio/ipc/participant.h"

namespace swlio::ipc {

struct PublisherOptions {
  /// Which topics get a writer (indexed by Topic). Publish* on a topic without one returns
  /// false and counts a failure. Under DDS Security a participant may create only the writers
  /// its permissions grant (an operator that publishes /initialpose: pose_topic "initialpose"
  /// and only kPose).
  std::array<bool, kTopicCount> topics = All();

  /// Every topic (the default: a new Topic gets a writer without an edit here).
  static std::array<bool, kTopicCount> All() {
    std::array<bool, kTopicCount> all{};
    all.fill(true);
    return all;
  }
};

class Publisher {
 public:
  /// Creates the topics and writers on `participant` (which must outlive the Publisher).
  /// Returns nullptr with `error` filled when a topic name is invalid or DDS refuses (under DDS
  /// Security: "Not Allowed By Security" when the permissions do not grant the topic).
  static std::unique_ptr<Publisher> Create(const Participant& participant,
                                           const IpcConfig& config,
                                           std::string* error) {
    return Create(participant, config, PublisherOptions(), error);
  }
  static std::unique_ptr<Publisher> Create(const Participant& participant,
                                           const IpcConfig& config,
                                           const PublisherOptions& options,
                                           std::string* error);
  ~Publisher();
  Publisher(const Publisher&) = delete;
  Publisher& operator=(const Publisher&) = delete;

  /// Each returns false (and counts a failure) when the stamp does not fit
  /// builtin_interfaces/Time or DDS refuses the write. Pose, odometry and a TFMessage of up to
  /// four transforms allocate nothing.
  bool PublishPose(const PoseWithCovarianceStamped& pose);
  bool PublishOdometry(const Odometry& odometry);
  /// The odom-frame odometry (odom_odometry_topic).
  bool PublishOdomOdometry(const Odometry& odometry);
  /// /tf (KEEP_LAST 100, volatile) and /tf_static (KEEP_LAST 1, latched: send every static
  /// transform in one message, as tf2_ros's StaticTransformBroadcaster does).
  bool PublishTf(const TFMessage& tf);
  bool PublishTfStatic(const TFMessage& tf);
  bool PublishHealth(const DiagnosticArray& health);
  bool PublishPath(const Path& path);
  /// A map cloud of several MB: Cyclone serializes it in this call (one copy of `map.data`) and
  /// sends it in fragments; readers that miss fragments get them repaired by the reliable
  /// protocol. The writer keeps the newest map for late joiners (TRANSIENT_LOCAL, KEEP_LAST 1).
  bool PublishMap(const PointCloud2& map);
  /// The current sweep (sweep_topic; false and a failure when it is off).
  bool PublishSweep(const PointCloud2& sweep);
  bool PublishesSweeps() const { return writers_[static_cast<size_t>(Topic::kSweep)] > 0; }

  /// Readers currently matched to the topic's writer, as Cyclone counts them (the count to
  /// trust: Fast DDS may report "matched" for a writer whose data it then refuses).
  int MatchedSubscriptions(Topic topic) const;
  /// The DDS topic name ("rt/...") of `topic`.
  const std::string& DdsTopicName(Topic topic) const { return names_[Index(topic)]; }

  uint64_t published() const { return published_.load(std::memory_order_relaxed); }
  uint64_t failures() const { return failures_.load(std::memory_order_relaxed); }

 private:
  Publisher() = default;
  static size_t Index(Topic topic) { return static_cast<size_t>(topic); }
  bool Count(bool ok);
  bool WriteTf(Topic topic, const TFMessage& tf);

  std::array<int32_t, kTopicCount> topics_{};   // dds_entity_t
  std::array<int32_t, kTopicCount> writers_{};  // dds_entity_t
  std::array<std::string, kTopicCount> names_;
  std::atomic<uint64_t> published_{0};
  std::atomic<uint64_t> failures_{0};
};

}  // namespace swlio::ipc
