// A ROS bag as swlio's sensor input (bag_input.h).

#include "swlio/daemon/recording/bag_input.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

#include "swlio/daemon/sensors/lidar_stage.h"
#include "swlio/drivers/bag/bag_open.h"
#include "swlio/estimator/imu/imu_interval_means.h"

namespace swlio::daemon {
namespace bag = drivers::bag;

namespace {

bool IsVelodyne(bag::RosMessageKind kind) { return kind == bag::RosMessageKind::kVelodyneScan; }

/// Why the LiDAR topic's packets cannot go through `model`'s decoder ("" when they can).
std::string PacketFamilyProblem(bag::RosMessageKind kind, const std::string& model) {
  if (kind == bag::RosMessageKind::kPointCloud2 || kind == bag::RosMessageKind::kUnknown) return {};
  const bool velodyne_model = model == "vlp16";
  if (IsVelodyne(kind) == velodyne_model) return {};
  return std::string("its packets are ") + (IsVelodyne(kind) ? "Velodyne" : "RoboSense") +
         " packets, and lidar.model is \"" + model + "\" (set lidar.model in --config to " +
         (IsVelodyne(kind) ? "vlp16" : "rs16 or helios16p") + ")";
}

/// Events in time order, each held until one `window_ns` newer has come (bag_input.h).
class ReorderBuffer {
 public:
  explicit ReorderBuffer(int64_t window_ns) : window_ns_(window_ns) {}

  /// `key_ns`: the time the event must be ordered at (a sweep's end).
  void Push(int64_t key_ns, RecordingEvent&& e) {
    // At one time an IMU sample goes before a fix or wheel sample, and those before a sweep.
    const int rank = e.kind == RecordingEvent::Kind::kImu    ? 0
                     : e.kind == RecordingEvent::Kind::kScan ? 2
                                                             : 1;
    newest_ns_ = std::max(newest_ns_, key_ns);
    events_.emplace(Key{key_ns, rank, seq_++}, std::move(e));
  }
  /// The oldest event when it is due (or when `all`, at the end of the bag).
  bool Pop(bool all, RecordingEvent* out) {
    if (events_.empty()) return false;
    auto first = events_.begin();
    if (!all && newest_ns_ - first->first.t_ns < window_ns_) return false;
    *out = std::move(first->second);
    events_.erase(first);
    return true;
  }

 private:
  struct Key {
    int64_t t_ns;
    int rank;
    uint64_t seq;
    bool operator<(const Key& o) const {
      return std::tie(t_ns, rank, seq) < std::tie(o.t_ns, o.rank, o.seq);
    }
  };
  int64_t window_ns_;
  int64_t newest_ns_ = std::numeric_limits<int64_t>::min();
  uint64_t seq_ = 0;
  std::map<Key, RecordingEvent> events_;
};

class BagInput : public SensorInput {
 public:
  BagInput(std::unique_ptr<bag::BagMessageStream> stream,
           const drivers::LidarConfig& lidar,
           const BagInputOptions& options)
      : stream_(std::move(stream)),
        lidar_config_(lidar),
        options_(options),
        buffer_(options.reorder_window_ns) {}

  bool Next(RecordingEvent* event) override {
    while (!buffer_.Pop(ended_, event)) {
      if (ended_) return false;
      bag::StreamMessage m;
      if (stream_->Next(&m)) {
        Take(m);
      } else {
        ended_ = true;
        if (stage_) {
          stage_->Flush();
          PopSweeps();
        }
      }
    }
    return true;
  }

  const RecordingStats& stats() const override { return stats_; }
  std::string Report() const override;

 private:
  /// The time `stamp_ns` (a header or packet stamp, 0 when unset) stands for under the options.
  int64_t Time(int64_t stamp_ns, const bag::StreamMessage& m) const {
    return options_.stamp == BagStamp::kReceive || stamp_ns <= 0 ? m.log_time_ns : stamp_ns;
  }
  void Take(const bag::StreamMessage& m);
  void TakePackets(const bag::LidarPacketsMsg& msg, const bag::StreamMessage& m);
  void TakeCloud(const bag::CloudPoints& cloud, const bag::StreamMessage& m);
  void TakeImu(const bag::ImuMsg& msg, const bag::StreamMessage& m);
  void TakeFix(const bag::NavSatFixMsg& msg, const bag::StreamMessage& m);
  void TakeWheel(int64_t stamp_ns,
                 double v_mps,
                 double yaw_rate_radps,
                 const bag::StreamMessage& m);
  void PopSweeps();

  std::unique_ptr<bag::BagMessageStream> stream_;
  drivers::LidarConfig lidar_config_;
  BagInputOptions options_;
  std::unique_ptr<LidarStage> stage_;  ///< created with the first packet message
  HostSweep sweep_;
  ReorderBuffer buffer_;
  RecordingStats stats_;
  estimator::ImuIntervalMeans imu_means_;  ///< BagImuSamples::kInstantaneous
  uint64_t cloud_seq_ = 0;
  uint64_t points_out_of_range_ = 0;
  bool ended_ = false;
};

void BagInput::Take(const bag::StreamMessage& m) {
  const bag::DecodedMessage& d = *m.decoded;
  switch (m.role) {
    case bag::TopicRole::kLidar:
      if (m.cloud != nullptr) {
        TakeCloud(*m.cloud, m);
      } else {
        TakePackets(d.packets, m);
      }
      return;
    case bag::TopicRole::kImu:
      TakeImu(d.imu, m);
      return;
    case bag::TopicRole::kGnss:
      if (options_.gnss) TakeFix(d.fix, m);
      return;
    case bag::TopicRole::kWheel:
      if (!options_.wheel) return;
      if (d.kind == bag::RosMessageKind::kOdometry) {
        TakeWheel(d.odometry.header.stamp_ns, d.odometry.linear_velocity_mps.x(),
                  d.odometry.angular_velocity_radps.z(), m);
      } else {
        TakeWheel(d.twist.header.stamp_ns, d.twist.linear_velocity_mps.x(),
                  d.twist.angular_velocity_radps.z(), m);
      }
      return;
    case bag::TopicRole::kNone:
      return;
  }
}

void BagInput::TakePackets(const bag::LidarPacketsMsg& msg, const bag::StreamMessage& m) {
  if (!stage_) stage_ = std::make_unique<LidarStage>(lidar_config_);
  const int64_t message_ns = msg.has_header ? msg.header.stamp_ns : 0;
  for (const bag::LidarPacketView& p : msg.packets) {
    stage_->Add(p.payload, Time(p.stamp_ns > 0 ? p.stamp_ns : message_ns, m));
    PopSweeps();
  }
}

void BagInput::PopSweeps() {
  while (stage_->Pop(&sweep_)) {
    RecordingEvent e;
    e.kind = RecordingEvent::Kind::kScan;
    e.scan = std::move(sweep_.scan);
    const int64_t end_ns = e.scan.t_end_ns;
    buffer_.Push(end_ns, std::move(e));
  }
  const LidarStageCounters& c = stage_->counters();
  stats_.lidar_packets = c.data_packets;
  stats_.scans = c.sweeps;
  stats_.partial_scans = c.partial_sweeps;
  stats_.missing_packets = c.missing_packets;
  stats_.lidar_clock = stage_->clock();
}

void BagInput::TakeCloud(const bag::CloudPoints& cloud, const bag::StreamMessage& m) {
  RecordingEvent e;
  e.kind = RecordingEvent::Kind::kScan;
  e.scan.seq = cloud_seq_++;
  const double min2 = lidar_config_.min_range_m * lidar_config_.min_range_m;
  const double max2 = lidar_config_.max_range_m * lidar_config_.max_range_m;
  e.scan.points.reserve(cloud.scan.points.size());
  for (const LidarPoint& p : cloud.scan.points) {
    const double r2 = p.xyz_m.cast<double>().squaredNorm();
    if (r2 < min2 || r2 > max2) {
      ++points_out_of_range_;
      continue;
    }
    e.scan.points.push_back(p);
  }
  if (e.scan.points.empty()) return;
  // Points keep their spacing; with receive times the sweep moves so that the header stamp
  // lands on the receive time.
  const int64_t shift_ns =
      options_.stamp == BagStamp::kReceive ? m.log_time_ns - m.decoded->cloud.header.stamp_ns : 0;
  int64_t first_dt = std::numeric_limits<int64_t>::max(), last_dt = 0;
  for (const LidarPoint& p : e.scan.points) {
    first_dt = std::min(first_dt, p.dt_ns);
    last_dt = std::max(last_dt, p.dt_ns);
  }
  for (LidarPoint& p : e.scan.points) p.dt_ns -= first_dt;
  e.scan.t_start_ns = cloud.scan.t_start_ns + first_dt + shift_ns;
  e.scan.t_end_ns = cloud.scan.t_start_ns + last_dt + shift_ns;
  ++stats_.scans;
  const int64_t end_ns = e.scan.t_end_ns;
  buffer_.Push(end_ns, std::move(e));
}

void BagInput::TakeImu(const bag::ImuMsg& msg, const bag::StreamMessage& m) {
  // sensor_msgs/Imu: covariance element 0 = −1 marks a quantity the sensor did not provide.
  if (msg.linear_acceleration_covariance[0] == -1.0 || msg.angular_velocity_covariance[0] == -1.0 ||
      !msg.linear_acceleration_mps2.allFinite() || !msg.angular_velocity_radps.allFinite()) {
    ++stats_.imu_dropped;
    return;
  }
  RecordingEvent e;
  e.kind = RecordingEvent::Kind::kImu;
  e.imu.t_ns = Time(msg.header.stamp_ns, m);
  e.imu.acc_mps2 = msg.linear_acceleration_mps2;
  e.imu.gyro_radps = msg.angular_velocity_radps;
  if (options_.imu_samples == BagImuSamples::kInstantaneous) e.imu = imu_means_.Next(e.imu);
  ++stats_.imu_samples;
  buffer_.Push(e.imu.t_ns, std::move(e));
}

void BagInput::TakeFix(const bag::NavSatFixMsg& msg, const bag::StreamMessage& m) {
  const auto& c = msg.position_covariance_m2;
  // sensor_msgs/NavSatFix: status −1 (−2 in Jazzy) = no fix; covariance type 0 = unknown.
  if (msg.status < 0 || msg.position_covariance_type == 0 || !(c[0] >= 0.0) || !(c[4] >= 0.0) ||
      !(c[8] >= 0.0)) {
    ++stats_.gnss_rejected;
    return;
  }
  RecordingEvent e;
  e.kind = RecordingEvent::Kind::kGnss;
  GnssFix& f = e.gnss;
  f.t_ns = Time(msg.header.stamp_ns, m);
  f.lat_deg = msg.latitude_deg;
  f.lon_deg = msg.longitude_deg;
  f.height_m = msg.altitude_m;
  f.h_acc_m = std::sqrt(std::max(c[0], c[4]));
  f.v_acc_m = std::sqrt(c[8]);
  // u-blox fixType as GnssFix states it: 3 (3-D) with a finite altitude, else 2 (2-D).
  f.fix_type = std::isfinite(msg.altitude_m) ? 3 : 2;
  ++stats_.gnss_fixes;
  buffer_.Push(f.t_ns, std::move(e));
}

void BagInput::TakeWheel(int64_t stamp_ns,
                         double v_mps,
                         double yaw_rate_radps,
                         const bag::StreamMessage& m) {
  if (!std::isfinite(v_mps) || !std::isfinite(yaw_rate_radps)) {
    ++stats_.wheel_frames_dropped;
    return;
  }
  RecordingEvent e;
  e.kind = RecordingEvent::Kind::kWheel;
  e.wheel = {Time(stamp_ns, m), v_mps, yaw_rate_radps};
  ++stats_.wheel_samples;
  buffer_.Push(e.wheel.t_ns, std::move(e));
}

std::string BagInput::Report() const {
  std::string out;
  const auto& topics = stream_->reader().topics();
  const bag::SelectedTopics& s = stream_->selected();
  for (const auto& t : {s.lidar, s.lidar_info, s.imu, s.gnss, s.wheel}) {
    if (!t) continue;
    const bag::TopicStreamStats& st = stream_->topic_stats(*t);
    out += topics[*t].name + ": " + std::to_string(st.delivered) + " messages read";
    if (st.skipped() > 0) out += ", " + std::to_string(st.skipped()) + " skipped";
    if (st.non_finite_points > 0)
      out += ", " + std::to_string(st.non_finite_points) + " non-finite points dropped";
    out += "\n";
  }
  if (points_out_of_range_ > 0)
    out += std::to_string(points_out_of_range_) + " cloud points outside the range limits\n";
  for (const std::string& w : stream_->reader().warnings()) out += w + "\n";
  for (const std::string& w : stream_->warnings()) out += w + "\n";
  if (!stream_->reader().error().empty()) out += "read error: " + stream_->reader().error() + "\n";
  return out;
}

}  // namespace

std::unique_ptr<SensorInput> OpenBagInput(const std::string& path,
                                          const drivers::LidarConfig& lidar,
                                          const BagInputOptions& options,
                                          std::string* error) {
  auto reader = bag::OpenBag(path, bag::BagReadLimits{}, error);
  if (!reader) return nullptr;
  bag::BagStreamOptions stream_options;
  stream_options.topics = options.topics;
  stream_options.cloud = options.cloud;
  auto stream = bag::BagMessageStream::Create(std::move(reader), stream_options, error);
  if (!stream) return nullptr;
  const bag::SelectedTopics& s = stream->selected();
  const auto& topics = stream->reader().topics();
  const auto missing = [&](const char* what, const char* option) {
    *error = path + ": no " + what + " topic (name one with " + option + ")";
    return nullptr;
  };
  if (!s.lidar) return missing("LiDAR packet or PointCloud2", "--lidar-topic");
  if (!s.imu && options.require_imu) return missing("sensor_msgs/Imu", "--imu-topic");
  if (options.gnss && !s.gnss) return missing("sensor_msgs/NavSatFix", "--gnss-topic");
  if (options.wheel && !s.wheel)
    return missing("nav_msgs/Odometry or TwistStamped", "--wheel-topic");
  const std::string problem =
      PacketFamilyProblem(bag::ClassifyTopic(topics[*s.lidar]), lidar.model);
  if (!problem.empty()) {
    *error = path + ": LiDAR topic " + topics[*s.lidar].name + ": " + problem;
    return nullptr;
  }
  return std::make_unique<BagInput>(std::move(stream), lidar, options);
}

bool IsRecordingFolder(const std::string& path) {
  std::error_code ec;
  for (const char* file : {"manifest.yaml", "lidar.pcap", "imu.xbus"}) {
    if (std::filesystem::is_regular_file(std::filesystem::path(path) / file, ec)) return true;
  }
  return false;
}

}  // namespace swlio::daemon
