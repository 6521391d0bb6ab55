// swlio-echo as a separate process: what it prints and records for samples that really cross
// loopback UDP from this process's Publisher. Domains 121..125, 136 and 137.
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "child_process.h"
#include "ipc_test_util.h"
#include "swlio/ipc/participant.h"
#include "swlio/ipc/point_cloud.h"
#include "swlio/ipc/publisher.h"
#include "test_data.h"

namespace swlio::ipc {
namespace {

#ifdef SWLIO_HAVE_ECHO
using test_util::ChildProcess;

std::vector<std::string> EchoArgs(int domain, std::vector<std::string> extra) {
  std::vector<std::string> args = {
      ::swlio::test::ToolPath("swlio-echo").string(), "--domain", std::to_string(domain),
      "--dds-config", (test::SourceDir() / "config" / "cyclonedds-loopback.xml").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

/// A Publisher on `domain` that waited until swlio-echo's reader of `topic` matched.
std::unique_ptr<Publisher> MatchedPublisher(int domain,
                                            Topic topic,
                                            std::unique_ptr<Participant>* participant) {
  const IpcConfig config = test_util::LoopbackConfig(domain);
  std::string error;
  *participant = Participant::Create(config, &error);
  EXPECT_NE(*participant, nullptr) << error;
  if (*participant == nullptr) return nullptr;
  auto publisher = Publisher::Create(**participant, config, &error);
  EXPECT_NE(publisher, nullptr) << error;
  if (publisher == nullptr) return nullptr;
  EXPECT_TRUE(test_util::WaitFor([&] { return publisher->MatchedSubscriptions(topic) > 0; }, 20.0))
      << "swlio-echo's reader did not match";
  return publisher;
}

/// Exact ns from a TUM stamp "[-]sec.nnnnnnnnn".
int64_t ParseStamp(const std::string& s) {
  const bool negative = s.front() == '-';
  const auto dot = s.find('.');
  const int64_t sec = std::stoll(s.substr(negative ? 1 : 0, dot - (negative ? 1 : 0)));
  const int64_t ns = sec * 1'000'000'000 + std::stoll(s.substr(dot + 1));
  return negative ? -ns : ns;
}

std::vector<std::string> Lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(EchoCli, RecordsPosesAsTumBitExactAndLatencyCsv) {
  const auto dir = test::MakeTempDir("echo");
  const auto tum = dir / "poses.tum";
  const auto csv = dir / "latency.csv";
  constexpr int kCount = 5;
  ChildProcess echo(
      EchoArgs(121, {"--topics", "pose", "--record", tum.string(), "--latency", csv.string(),
                     "--quiet", "--count", std::to_string(kCount), "--duration", "30"}));
  ASSERT_TRUE(echo.running());
  std::unique_ptr<Participant> participant;
  auto publisher = MatchedPublisher(121, Topic::kPose, &participant);
  ASSERT_NE(publisher, nullptr);
  const std::vector<int64_t> stamps = {-1, -1'500'000'000, 0, 1'700'000'000'000'000'001,
                                       2'147'483'647'999'999'999};
  std::vector<PoseWithCovarianceStamped> sent;
  for (int i = 0; i < kCount; ++i) {
    sent.push_back(test_util::MakePose(i, stamps[static_cast<size_t>(i)]));
    // TUM is text: NaN payloads and infinities have no exact decimal form; keep these finite.
    sent.back().pose.position_m = {-0.0, 1.0 / 3.0 + i, std::numeric_limits<double>::denorm_min()};
    sent.back().pose.orientation_xyzw = {0.1 * i, -std::numeric_limits<double>::max(), 1e-300,
                                         std::nextafter(1.0, 0.0)};
    ASSERT_TRUE(publisher->PublishPose(sent.back()));
  }
  ASSERT_EQ(echo.Wait(), 0);

  const auto tum_lines = Lines(tum);
  ASSERT_EQ(tum_lines.size(), 1u + kCount);
  EXPECT_EQ(tum_lines[0], "# timestamp tx ty tz qx qy qz qw");
  for (size_t i = 0; i < sent.size(); ++i) {
    std::istringstream in(tum_lines[i + 1]);
    std::string stamp;
    in >> stamp;
    EXPECT_EQ(ParseStamp(stamp), sent[i].t_ns) << stamp;
    Pose got;
    for (double& v : got.position_m) in >> v;
    for (double& v : got.orientation_xyzw) in >> v;
    EXPECT_TRUE(test_util::SamePose(got, sent[i].pose)) << tum_lines[i + 1];
  }
  const auto csv_lines = Lines(csv);
  ASSERT_EQ(csv_lines.size(), 1u + kCount);
  EXPECT_EQ(csv_lines[0].rfind("topic,stamp_ns,", 0), 0u);
  EXPECT_EQ(csv_lines[1].rfind("pose,-1,", 0), 0u) << csv_lines[1];
}

TEST(EchoCli, PrintsOneLinePerSampleOfEveryTopic) {
  ChildProcess echo(EchoArgs(122, {"--count", "4", "--duration", "30"}));
  ASSERT_TRUE(echo.running());
  std::unique_ptr<Participant> participant;
  auto publisher = MatchedPublisher(122, Topic::kPath, &participant);
  ASSERT_NE(publisher, nullptr);
  ASSERT_TRUE(test_util::WaitFor([&] {
    return publisher->MatchedSubscriptions(Topic::kPose) > 0 &&
           publisher->MatchedSubscriptions(Topic::kOdometry) > 0 &&
           publisher->MatchedSubscriptions(Topic::kHealth) > 0;
  }));
  ASSERT_TRUE(publisher->PublishPose(test_util::MakePose(1, 1'000'000'000)));
  Odometry odometry;
  odometry.t_ns = 2'000'000'000;
  odometry.frame_id = "odom";
  odometry.child_frame_id = "imu_link";
  ASSERT_TRUE(publisher->PublishOdometry(odometry));
  DiagnosticArray health;
  health.t_ns = 3'000'000'000;
  health.status.push_back({DiagnosticLevel::kWarn, "swlio: lidar", "late", "rs16", {{"gap", "3"}}});
  ASSERT_TRUE(publisher->PublishHealth(health));
  Path path;
  path.t_ns = 4'000'000'000;
  path.frame_id = "map";
  path.poses.resize(3);
  ASSERT_TRUE(publisher->PublishPath(path));

  std::vector<std::string> lines(4);
  for (auto& line : lines) ASSERT_TRUE(echo.ReadLine(&line, 20.0));
  EXPECT_EQ(echo.Wait(), 0);
  // The echo takes topic by topic, so lines may come in any order; sort by their first word.
  std::sort(lines.begin(), lines.end());
  EXPECT_EQ(lines[0].rfind("health t=3.000000000 n=1 | swlio: lidar WARN \"late\" gap=3", 0), 0u)
      << lines[0];
  EXPECT_EQ(lines[1].rfind("odometry t=2.000000000 frame=odom child=imu_link p=[0 0 0]", 0), 0u)
      << lines[1];
  EXPECT_EQ(lines[2].rfind("path t=4.000000000 frame=map poses=3", 0), 0u) << lines[2];
  EXPECT_EQ(lines[3].rfind("pose t=1.000000000 frame=map p=[", 0), 0u) << lines[3];
}

// --record-path keeps only the last path (after a loop the daemon republishes the whole graph).
TEST(EchoCli, RecordPathWritesTheLastPathReceived) {
  const auto dir = test::MakeTempDir("echo");
  const auto tum = dir / "path.tum";
  ChildProcess echo(EchoArgs(137, {"--topics", "path", "--record-path", tum.string(), "--count",
                                   "2", "--duration", "30"}));
  ASSERT_TRUE(echo.running());
  std::unique_ptr<Participant> participant;
  auto publisher = MatchedPublisher(137, Topic::kPath, &participant);
  ASSERT_NE(publisher, nullptr);
  Path path;
  path.frame_id = "map";
  for (int i = 0; i < 3; ++i) {
    PoseStamped p;
    p.t_ns = 1'000'000'000LL * (i + 1);
    p.pose.position_m = {10.0 + i, 0.0, 0.0};
    path.poses.push_back(p);
  }
  ASSERT_TRUE(publisher->PublishPath(path));
  path.poses.pop_back();  // the graph moved: the first two nodes elsewhere, the third gone
  path.poses[0].pose.position_m = {-1.25, 2.0, 0.5};
  path.poses[1].pose.position_m = {-2.5, 4.0, 1.0};
  std::string line;
  ASSERT_TRUE(echo.ReadLine(&line, 20.0));  // the first one is in (the reader keeps only one)
  EXPECT_EQ(line.rfind("path t=0.000000000 frame=map poses=3", 0), 0u) << line;
  ASSERT_TRUE(publisher->PublishPath(path));
  ASSERT_EQ(echo.Wait(), 0);
  const auto lines = Lines(tum);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].rfind("# timestamp tx ty tz qx qy qz qw", 0), 0u) << lines[0];
  for (size_t i = 0; i < 2; ++i) {
    std::istringstream in(lines[i + 1]);
    std::string stamp;
    in >> stamp;
    EXPECT_EQ(ParseStamp(stamp), path.poses[i].t_ns) << stamp;
    Pose got;
    for (double& v : got.position_m) in >> v;
    for (double& v : got.orientation_xyzw) in >> v;
    EXPECT_TRUE(test_util::SamePose(got, path.poses[i].pose)) << lines[i + 1];
  }
}

TEST(EchoCli, RecordPathWithoutThePathTopicIsRefused) {
  const auto dir = test::MakeTempDir("echo");
  ChildProcess echo(EchoArgs(
      125, {"--topics", "pose", "--record-path", (dir / "p.tum").string(), "--duration", "5"}));
  EXPECT_EQ(echo.Wait(), 1);
  EXPECT_FALSE(std::filesystem::exists(dir / "p.tum"));
}

std::string Shortest(double v) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, v).ptr);
}

TEST(EchoCli, LateEchoGetsTheLatchedMapOverLoopbackUdp) {
  // 200,000 points (2.4 MB, ~1,800 UDP fragments) published before swlio-echo exists: its
  // TRANSIENT_LOCAL reader gets the map from the writer's history across loopback UDP.
  const IpcConfig config = test_util::LoopbackConfig(136);
  std::string error;
  auto participant = Participant::Create(config, &error);
  ASSERT_NE(participant, nullptr) << error;
  auto publisher = Publisher::Create(*participant, config, &error);
  ASSERT_NE(publisher, nullptr) << error;
  PointCloud2 map;
  map.t_ns = 7'000'000'001;
  map.frame_id = "map";
  constexpr size_t kPoints = 200'000;
  ASSERT_TRUE(InitXyzCloud(kPoints, false, &map));
  std::array<double, 3> lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < kPoints; ++i) {
    const float t = static_cast<float>(i) * 1e-3f;
    const std::array<float, 3> p = {t * std::cos(t), t * std::sin(t), 0.25f * t - 3.0f};
    SetPoint(i, p, 0.0f, &map);
    for (size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], static_cast<double>(p[a]));
      hi[a] = std::max(hi[a], static_cast<double>(p[a]));
    }
  }
  ASSERT_TRUE(publisher->PublishMap(map));
  ChildProcess echo(EchoArgs(136, {"--topics", "map", "--count", "1", "--duration", "30"}));
  ASSERT_TRUE(echo.running());
  std::string line;
  ASSERT_TRUE(echo.ReadLine(&line, 40.0)) << "the latched map did not arrive";
  EXPECT_EQ(echo.Wait(), 0);
  auto box = [](const std::array<double, 3>& v) {
    return "[" + Shortest(v[0]) + " " + Shortest(v[1]) + " " + Shortest(v[2]) + "]";
  };
  EXPECT_EQ(line,
            "map t=7.000000001 frame=map points=200000 (200000x1) bytes=2400000 point_step=12 "
            "fields=x,y,z min=" +
                box(lo) + " max=" + box(hi));
}

TEST(EchoCli, RefusesNonLoopbackConfig) {
  const auto dir = test::MakeTempDir("echo");
  std::ifstream in(test::SourceDir() / "config" / "cyclonedds-loopback.xml");
  std::stringstream xml;
  xml << in.rdbuf();
  std::string text = xml.str();
  text.replace(text.find("name=\"lo\""), 9, "name=\"eth0\"");
  std::ofstream(dir / "eth0.xml") << text;
  ChildProcess echo({::swlio::test::ToolPath("swlio-echo").string(), "--domain", "123",
                     "--dds-config", (dir / "eth0.xml").string(), "--duration", "5"});
  EXPECT_EQ(echo.Wait(), 1);
}

TEST(EchoCli, RecordWithoutItsTopicIsRefused) {
  const auto dir = test::MakeTempDir("echo");
  ChildProcess echo(EchoArgs(
      125, {"--topics", "health", "--record", (dir / "p.tum").string(), "--duration", "5"}));
  EXPECT_EQ(echo.Wait(), 1);
  EXPECT_FALSE(std::filesystem::exists(dir / "p.tum"));
}

TEST(EchoCli, CountNotReachedWithinDurationExitsTwo) {
  ChildProcess echo(EchoArgs(124, {"--count", "1", "--duration", "0.3"}));
  EXPECT_EQ(echo.Wait(), 2);
}
#else
TEST(EchoCli, NotBuilt) { GTEST_SKIP() << "swlio-echo is not built in this configuration"; }
#endif

}  // namespace
}  // namespace swlio::ipc
