// swlio-echo: subscribe to swlio's DDS topics and print one line per sample, or record the
// poses as a TUM trajectory, the last keyframe path (after loop closure: the pose graph's
// nodes) as another, and the delivery latencies as CSV. Loopback only: the Cyclone DDS
// configuration must keep all traffic on 127.0.0.1 (Participant refuses anything else).
//
// Exit codes: 0 done (--count reached, --duration over, or SIGINT/SIGTERM), 1 setup error,
// 2 --count samples did not arrive within --duration.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "echo_format.h"
#include "latency_summary.h"
#include "swlio/core/time.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/subscriber.h"

namespace swlio::tools::echo {
namespace {

using ipc::Topic;

std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop = true; }

struct EchoOptions {
  ipc::IpcConfig ipc;
  std::vector<std::string> topics{"pose", "odometry", "health", "path", "map"};
  std::string record_tum;
  std::string record_from = "pose";
  std::string record_path_tum;
  std::string latency_csv;
  std::string latency_summary_csv;
  double summary_period_s = 10.0;
  bool quiet = false;
  double duration_s = 0.0;
  int64_t count = 0;
};

/// Where received samples go: stdout, the TUM file, the latency CSV, and the counters.
class Sink {
 public:
  explicit Sink(const EchoOptions& options) : options_(options) {}

  bool Open(std::string* error) {
    if (!options_.record_tum.empty()) {
      tum_.open(options_.record_tum);
      if (!tum_) return Fail(error, "cannot write " + options_.record_tum);
      tum_ << kTumHeader << "\n";
    }
    if (!options_.latency_csv.empty()) {
      csv_.open(options_.latency_csv);
      if (!csv_) return Fail(error, "cannot write " + options_.latency_csv);
      csv_ << kLatencyHeader << "\n";
    }
    if (!options_.latency_summary_csv.empty()) {
      summary_csv_.open(options_.latency_summary_csv);
      if (!summary_csv_) return Fail(error, "cannot write " + options_.latency_summary_csv);
      summary_.emplace(&summary_csv_, options_.summary_period_s);
    }
    return true;
  }

  template <typename Message>
  void Handle(Topic topic, const std::vector<ipc::Received<Message>>& samples) {
    for (const auto& r : samples) {
      if (!options_.quiet) std::cout << FormatLine(r.msg) << "\n";
      if (csv_.is_open()) csv_ << LatencyRow(topic, r) << "\n";
      if (summary_) {
        summary_->Add(topic, r.receive_steady_ns, r.receive_realtime_ns - r.source_realtime_ns,
                      StampAgeNs(r));
      }
      if (tum_.is_open() && options_.record_from == ipc::TopicLabel(topic)) Record(r.msg);
      Keep(r.msg);
      if (topic == Topic::kPose)
        transport_ns_.push_back(r.receive_realtime_ns - r.source_realtime_ns);
      ++counts_[static_cast<size_t>(topic)];
      ++total_;
    }
    if (!samples.empty()) std::cout.flush();
  }

  int64_t total() const { return total_; }

  /// The last keyframe path received, as TUM (--record-path); false with *error.
  bool WritePath(std::string* error) const {
    if (options_.record_path_tum.empty()) return true;
    if (!last_path_)
      return Fail(error, "no path received: " + options_.record_path_tum + " not written");
    std::ofstream out(options_.record_path_tum);
    out << kTumHeader << "  (" << last_path_->frame_id << "; the last path received)\n";
    for (const ipc::PoseStamped& p : last_path_->poses) out << TumLine(p.t_ns, p.pose) << "\n";
    return static_cast<bool>(out) || Fail(error, "cannot write " + options_.record_path_tum);
  }

  /// Counts per topic and the pose write→take latency percentiles, to stderr.
  void Summary() {
    if (summary_) summary_->Flush();
    std::fprintf(stderr,
                 "swlio-echo: pose %lld, odometry %lld, health %lld, path %lld, map %lld samples",
                 static_cast<long long>(counts_[0]), static_cast<long long>(counts_[1]),
                 static_cast<long long>(counts_[2]), static_cast<long long>(counts_[3]),
                 static_cast<long long>(counts_[4]));
    for (const Topic t : {Topic::kOdomOdometry, Topic::kTf, Topic::kTfStatic}) {
      const int64_t n = counts_[static_cast<size_t>(t)];
      if (n > 0) std::fprintf(stderr, ", %s %lld", ipc::TopicLabel(t), static_cast<long long>(n));
    }
    if (!transport_ns_.empty()) {
      std::sort(transport_ns_.begin(), transport_ns_.end());
      auto at = [&](double q) {
        const auto i = static_cast<size_t>(q * static_cast<double>(transport_ns_.size() - 1));
        return static_cast<double>(transport_ns_[i]) * 1e-3;
      };
      std::fprintf(stderr, "; pose write->take latency p50 %.1f us, p99 %.1f us, max %.1f us",
                   at(0.5), at(0.99), at(1.0));
    }
    std::fprintf(stderr, "\n");
  }

 private:
  static bool Fail(std::string* error, const std::string& message) {
    *error = message;
    return false;
  }
  void Record(const ipc::PoseWithCovarianceStamped& m) { tum_ << TumLine(m.t_ns, m.pose) << "\n"; }
  void Record(const ipc::Odometry& m) { tum_ << TumLine(m.t_ns, m.pose) << "\n"; }
  template <typename Other>
  void Record(const Other&) {}
  void Keep(const ipc::Path& m) { last_path_ = m; }
  template <typename Other>
  void Keep(const Other&) {}

  const EchoOptions& options_;
  std::ofstream tum_;
  std::ofstream csv_;
  std::ofstream summary_csv_;
  std::optional<LatencySummary> summary_;
  std::array<int64_t, ipc::kTopicCount> counts_{};
  int64_t total_ = 0;
  std::vector<int64_t> transport_ns_;
  std::optional<ipc::Path> last_path_;
};

void AddOptions(CLI::App& app, EchoOptions& o) {
  app.add_option("--dds-config", o.ipc.dds_config_file, "Cyclone DDS XML (must be loopback-only)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  app.add_option("--domain", o.ipc.domain_id, "DDS domain id (ROS_DOMAIN_ID)")
      ->capture_default_str();
  app.add_option("--topics", o.topics, "which topics to read")
      ->delimiter(',')
      ->check(CLI::IsMember({"pose", "odometry", "health", "path", "map", "odom_odometry", "tf",
                             "tf_static", "sweep"}))
      ->capture_default_str();
  app.add_option("--pose-topic", o.ipc.pose_topic, "ROS 2 name (DDS adds rt/)")
      ->capture_default_str();
  app.add_option("--odometry-topic", o.ipc.odometry_topic)->capture_default_str();
  app.add_option("--health-topic", o.ipc.health_topic)->capture_default_str();
  app.add_option("--path-topic", o.ipc.path_topic)->capture_default_str();
  app.add_option("--map-topic", o.ipc.map_topic)->capture_default_str();
  app.add_option("--odom-odometry-topic", o.ipc.odom_odometry_topic)->capture_default_str();
  app.add_option("--tf-topic", o.ipc.tf_topic)->capture_default_str();
  app.add_option("--tf-static-topic", o.ipc.tf_static_topic)->capture_default_str();
  app.add_option("--record", o.record_tum, "write received poses to this TUM file");
  app.add_option("--record-from", o.record_from, "topic whose poses --record writes")
      ->check(CLI::IsMember({"pose", "odometry", "odom_odometry"}))
      ->capture_default_str();
  app.add_option("--record-path", o.record_path_tum,
                 "at exit, write the last keyframe path received (with loop closure: the pose "
                 "graph's nodes) to this TUM file");
  app.add_option("--latency", o.latency_csv, "write one latency CSV row per sample");
  app.add_option("--latency-summary", o.latency_summary_csv,
                 "write latency percentiles per topic every --summary-period (long runs)");
  app.add_option("--summary-period", o.summary_period_s, "seconds per --latency-summary row")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("--quiet,-q", o.quiet, "do not print samples");
  app.add_option("--duration", o.duration_s, "exit after this many seconds (0: no limit)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--count", o.count, "exit after this many samples in total (0: no limit)")
      ->check(CLI::NonNegativeNumber);
}

int Run(EchoOptions& options) {
  ipc::SubscriberOptions sub_options;
  for (size_t i = 0; i < ipc::kTopicCount; ++i) {
    const char* label = ipc::TopicLabel(static_cast<Topic>(i));
    sub_options.topics[i] =
        std::find(options.topics.begin(), options.topics.end(), label) != options.topics.end();
  }
  if (!options.record_tum.empty() && std::find(options.topics.begin(), options.topics.end(),
                                               options.record_from) == options.topics.end()) {
    std::cerr << "swlio-echo: --record needs the " << options.record_from << " topic in --topics\n";
    return 1;
  }
  if (!options.record_path_tum.empty() &&
      std::find(options.topics.begin(), options.topics.end(), "path") == options.topics.end()) {
    std::cerr << "swlio-echo: --record-path needs the path topic in --topics\n";
    return 1;
  }
  std::string error;
  auto participant = ipc::Participant::Create(options.ipc, &error);
  std::unique_ptr<ipc::Subscriber> subscriber;
  if (participant != nullptr) {
    subscriber = ipc::Subscriber::Create(*participant, options.ipc, sub_options, &error);
  }
  Sink sink(options);
  if (subscriber == nullptr || !sink.Open(&error)) {
    std::cerr << "swlio-echo: " << error << "\n";
    return 1;
  }
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(options.duration_s));
  int code = 0;
  while (!g_stop && (options.count == 0 || sink.total() < options.count)) {
    if (options.duration_s > 0.0 && std::chrono::steady_clock::now() >= deadline) {
      code = options.count > 0 ? 2 : 0;
      break;
    }
    subscriber->Wait(100 * kNsPerMs);
    sink.Handle(Topic::kPose, subscriber->TakePoses());
    sink.Handle(Topic::kOdometry, subscriber->TakeOdometry());
    sink.Handle(Topic::kHealth, subscriber->TakeHealth());
    sink.Handle(Topic::kPath, subscriber->TakePaths());
    sink.Handle(Topic::kMap, subscriber->TakeMaps());
    sink.Handle(Topic::kOdomOdometry, subscriber->TakeOdomOdometry());
    sink.Handle(Topic::kTf, subscriber->TakeTf());
    sink.Handle(Topic::kTfStatic, subscriber->TakeTfStatic());
    sink.Handle(Topic::kSweep, subscriber->TakeSweeps());
  }
  sink.Summary();
  if (!sink.WritePath(&error)) {
    std::cerr << "swlio-echo: " << error << "\n";
    code = code == 0 ? 1 : code;
  }
  if (code == 2) std::cerr << "swlio-echo: --count not reached within --duration\n";
  return code;
}

}  // namespace
}  // namespace swlio::tools::echo

namespace {

int Main(int argc, char** argv) {
  CLI::App app{"swlio-echo: print or record swlio's DDS topics (loopback only)"};
  swlio::tools::echo::EchoOptions options;
  options.ipc.dds_config_file = SWLIO_DEFAULT_DDS_CONFIG;
  swlio::tools::echo::AddOptions(app, options);
  CLI11_PARSE(app, argc, argv);
  const auto issues = options.ipc.Validate();
  if (!issues.empty()) {
    std::cerr << "swlio-echo: " << issues.front().key << ": " << issues.front().reason << "\n";
    return 1;
  }
  return swlio::tools::echo::Run(options);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", "swlio-echo", e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown exception\n", "swlio-echo");
  }
  return 1;
}
