#pragma once
/// @file
/// Reads swlio's topics (for swlio-echo and tests): decoded samples with their receive times.
/// Cyclone DDS stays behind this header. Reader QoS requests what the writers offer (see
/// qos_profile.h): RELIABLE, KEEP_LAST `history_depth`, VOLATILE except the path, the map and
/// /tf_static, which are TRANSIENT_LOCAL so a late subscriber still gets the last keyframe path,
/// map and static transforms.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "swlio/ipc/ipc_config.h"
#include "swlio/ipc/messages.h"
#include "swlio/ipc/participant.h"

namespace swlio::ipc {

struct SubscriberOptions {
  /// Reader history per topic: samples not yet taken beyond this many are overwritten.
  int history_depth = 100;
  /// The map and sweep readers' history: maps are MBs each, sweeps hundreds of kB, and each
  /// supersedes the last, so a reader that falls behind keeps only the newest.
  int map_history_depth = 1;
  /// Which topics to read (indexed by Topic).
  std::array<bool, kTopicCount> topics = All();

  static std::array<bool, kTopicCount> All() {
    std::array<bool, kTopicCount> all{};
    all.fill(true);
    return all;
  }
};

class Subscriber {
 public:
  /// Creates the readers on `participant` (which must outlive the Subscriber).
  static std::unique_ptr<Subscriber> Create(const Participant& participant,
                                            const IpcConfig& config,
                                            const SubscriberOptions& options,
                                            std::string* error);
  ~Subscriber();
  Subscriber(const Subscriber&) = delete;
  Subscriber& operator=(const Subscriber&) = delete;

  /// Blocks until some subscribed topic has unread data or `timeout_ns` passes; true if data.
  bool Wait(int64_t timeout_ns);

  /// Take everything received so far on one topic (empty when the topic is not subscribed).
  /// The receive time is taken once per call, right after the samples leave DDS.
  std::vector<Received<PoseWithCovarianceStamped>> TakePoses();
  std::vector<Received<Odometry>> TakeOdometry();
  std::vector<Received<DiagnosticArray>> TakeHealth();
  std::vector<Received<Path>> TakePaths();
  std::vector<Received<PointCloud2>> TakeMaps();
  std::vector<Received<PointCloud2>> TakeSweeps();
  std::vector<Received<Odometry>> TakeOdomOdometry();
  std::vector<Received<TFMessage>> TakeTf();
  std::vector<Received<TFMessage>> TakeTfStatic();

  /// Writers currently matched to the topic's reader (0 when not subscribed).
  int MatchedPublications(Topic topic) const;
  /// Samples received that could not be decoded (a stamp with nanosec ≥ 1e9 from a foreign
  /// writer); they are dropped.
  uint64_t decode_failures() const { return decode_failures_; }

 private:
  Subscriber() = default;
  template <typename Message, typename Wire>
  std::vector<Received<Message>> Take(Topic topic);

  std::array<int32_t, kTopicCount> topics_{};   // dds_entity_t, 0 when not subscribed
  std::array<int32_t, kTopicCount> readers_{};  // dds_entity_t, 0 when not subscribed
  int32_t waitset_ = 0;
  uint64_t decode_failures_ = 0;
};

}  // namespace swlio::ipc
