// ROS bags as swlio-run's input, end to end: a simulated recording exported with
// `swlio-bag export` to MCAP (and, by this test, to a ROS 1 .bag and a rosbag2 .db3 of the same
// messages) runs to the same accuracy as the recording itself; a bag without the topics a run
// needs is refused with the option to use.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "../drivers/support/db3_builder.h"
#include "../drivers/support/ros1_bag_writer.h"
#include "shared_sim_recording.h"
#include "swlio/drivers/bag/bag_open.h"
#include "swlio/drivers/bag/message_decoder.h"
#include "swlio/drivers/bag/message_encoder.h"
#include "swlio/eval/evaluate.h"
#include "test_data.h"

namespace swlio {
namespace {

namespace fs = std::filesystem;
namespace bag = drivers::bag;

/// The messages of `mcap` re-encoded for ROS 1 (the types swlio reads; /tf_static is left
/// out), written as an LZ4-compressed .bag, and copied as they are into a schema-3 .db3.
void ConvertMcap(const fs::path& mcap, const fs::path& ros1, const fs::path& db3) {
  std::string error;
  auto reader = bag::OpenBag(mcap.string(), {}, &error);
  ASSERT_NE(reader, nullptr) << error;
  test::Ros1BagWriter writer("lz4", 1 << 20);
  std::vector<test::Db3Topic> topics;
  std::vector<test::Db3Message> rows;
  std::vector<bag::RosMessageKind> kinds;
  for (uint32_t i = 0; i < reader->topics().size(); ++i) {
    const bag::BagTopic& t = reader->topics()[i];
    kinds.push_back(bag::ClassifyTopic(t));
    topics.push_back({i + 1, t.name, t.type, "cdr", ""});
    writer.AddConnection({i + 1, t.name, bag::NormalizeTypeName(t.type), "*", ""});
  }
  bag::BagMessage m;
  bag::DecodedMessage d;
  while (reader->Next(&m)) {
    rows.push_back({m.topic + 1, m.log_time_ns, {m.data.begin(), m.data.end()}});
    if (kinds[m.topic] == bag::RosMessageKind::kUnknown) continue;
    ASSERT_TRUE(bag::DecodeMessage(kinds[m.topic], bag::MessageEncoding::kCdr, m.data, &d, &error))
        << error;
    constexpr auto kRos1 = bag::MessageEncoding::kRos1;
    switch (d.kind) {
      case bag::RosMessageKind::kPointCloud2:
        writer.Write(m.topic + 1, m.log_time_ns, bag::EncodePointCloud2(d.cloud, kRos1));
        break;
      case bag::RosMessageKind::kImu:
        writer.Write(m.topic + 1, m.log_time_ns, bag::EncodeImu(d.imu, kRos1));
        break;
      case bag::RosMessageKind::kNavSatFix:
        writer.Write(m.topic + 1, m.log_time_ns, bag::EncodeNavSatFix(d.fix, kRos1));
        break;
      case bag::RosMessageKind::kOdometry:
        writer.Write(m.topic + 1, m.log_time_ns, bag::EncodeOdometry(d.odometry, kRos1));
        break;
      default:
        FAIL() << "unexpected message kind on " << reader->topics()[m.topic].name;
    }
  }
  ASSERT_TRUE(reader->error().empty()) << reader->error();
  const std::vector<uint8_t> bytes = writer.Finish();
  std::ofstream(ros1, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  test::WriteDb3(db3, 3, topics, rows);
}

eval::Evaluation Ape(const fs::path& groundtruth, const fs::path& est) {
  eval::ApeOptions options;
  options.alignment = eval::Alignment::kSe3;
  return eval::EvaluateApe(eval::LoadPaired(groundtruth, est, eval::Format::kTum), options);
}

struct Drive {
  const char* scenario;
  double duration_s;
};
void PrintTo(const Drive& d, std::ostream* os) {
  *os << d.scenario << ", " << d.duration_s << " s";
}

class BagInputOnDrive : public ::testing::TestWithParam<Drive> {};

/// The drive's length: the parameter's, or SWLIO_BAG_DRIVE_S seconds when set (0: the whole
/// scenario, for the figures in docs/notes/2026-12-03-ros-bags.md).
double DriveSeconds(double fallback) {
  const char* env = std::getenv("SWLIO_BAG_DRIVE_S");
  if (env == nullptr) return fallback;
  const double s = std::atof(env);
  return s > 0.0 ? s : 1e5;  // longer than any route: not cut
}

// Seed 1 of each scenario, cut to 20–25 s so that the test stays short.
TEST_P(BagInputOnDrive, ExportedBagsRunAsTheRecording) {
  const std::string run = test::ToolPath("swlio-run").string();
  const std::string export_tool = test::ToolPath("swlio-bag").string();
  if (run.empty() || export_tool.empty()) GTEST_SKIP() << "swlio-run / swlio-bag not built";
  std::string error;
  const fs::path rec =
      test::SharedSimRecording(GetParam().scenario, 1, DriveSeconds(GetParam().duration_s), &error);
  ASSERT_FALSE(rec.empty()) << error;
  const fs::path out = test::MakeTempDir(std::string("swlio_bag_") + GetParam().scenario);
  int code = 0;
  std::string log = test::RunCommand(
      export_tool + " export " + rec.string() + " " + (out / "drive.mcap").string() + " 2>&1",
      &code);
  ASSERT_EQ(code, 0) << log;
  ConvertMcap(out / "drive.mcap", out / "drive.bag", out / "drive.db3");

  std::map<std::string, double> rmse;
  for (const char* input : {"", "drive.mcap", "drive.bag", "drive.db3"}) {
    const fs::path in = *input == '\0' ? rec : out / input;
    // A bag carries no rig: the export wrote the recording's beside the MCAP.
    const std::string config =
        *input == '\0' ? "" : " --config " + (out / "drive.swlio.yaml").string();
    const fs::path est = out / (std::string(*input == '\0' ? "raw" : input) + ".tum");
    log = test::RunCommand(
        run + " " + in.string() + config + " --loop-closure off --out " + est.string() + " 2>&1",
        &code);
    ASSERT_EQ(code, 0) << in << ": " << log;
    const eval::Evaluation ape = Ape(rec / "groundtruth.tum", est);
    ASSERT_GE(ape.errors.size(), 150u) << in << ": " << log;
    rmse[*input == '\0' ? "raw" : input] = ape.stats.rmse;
    std::cout << GetParam().scenario << " " << (*input == '\0' ? "recording" : input)
              << ": APE RMSE " << ape.stats.rmse << " m over " << ape.errors.size() << " poses\n";
  }
  const double raw = rmse["raw"];
  EXPECT_LT(raw, 0.1);
  for (const char* input : {"drive.mcap", "drive.bag", "drive.db3"}) {
    EXPECT_NEAR(rmse[input], raw, 0.02 * raw) << input << " against the recording";
  }
}

INSTANTIATE_TEST_SUITE_P(Scenarios,
                         BagInputOnDrive,
                         ::testing::Values(Drive{"short", 25.0},
                                           Drive{"aggressive", 20.0},
                                           Drive{"loop943", 20.0}),
                         [](const auto& info) { return std::string(info.param.scenario); });

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// swlio-replay on an exported bag: --deterministic gives byte-identical trajectories, and the
// same poses as swlio-run on that bag (both run the one EstimatorRunner on the one input).
TEST(BagInputCommand, DeterministicReplayOfABagMatchesSwlioRun) {
  const std::string run = test::ToolPath("swlio-run").string();
  const std::string replay = test::ToolPath("swlio-replay").string();
  const std::string export_tool = test::ToolPath("swlio-bag").string();
  if (run.empty() || replay.empty() || export_tool.empty()) GTEST_SKIP() << "tools not built";
  std::string error;
  const fs::path rec = test::SharedSimRecording("short", 1, 25.0, &error);
  ASSERT_FALSE(rec.empty()) << error;
  const fs::path out = test::MakeTempDir("swlio_bag_replay");
  int code = 0;
  std::string log = test::RunCommand(
      export_tool + " export " + rec.string() + " " + (out / "d.mcap").string() + " 2>&1", &code);
  ASSERT_EQ(code, 0) << log;
  const std::string bag =
      (out / "d.mcap").string() + " --config " + (out / "d.swlio.yaml").string();
  for (const char* name : {"a.tum", "b.tum"}) {
    log = test::RunCommand(
        replay + " " + bag + " --deterministic --out " + (out / name).string() + " 2>&1", &code);
    ASSERT_EQ(code, 0) << log;
  }
  log = test::RunCommand(
      run + " " + bag + " --loop-closure off --out " + (out / "run.tum").string() + " 2>&1", &code);
  ASSERT_EQ(code, 0) << log;
  const std::string a = ReadFile(out / "a.tum");
  EXPECT_GT(a.size(), 10'000u);
  EXPECT_EQ(a, ReadFile(out / "b.tum"));
  EXPECT_EQ(a, ReadFile(out / "run.tum"));
}

// The real washing_house bag holds the LiDAR alone; its sweeps are checked against its capture
// in daemon.BagInput.WashingHouseBagGivesThePcapSweeps. Both estimator modes need an IMU.
TEST(BagInputCommand, ABagWithoutImuIsRefused) {
  const std::string run = test::ToolPath("swlio-run").string();
  if (run.empty()) GTEST_SKIP() << "swlio-run not built";
  SWLIO_REQUIRE_DATA(dir, "rs16_washing_house/metadata.yaml");
  int code = 0;
  const std::string log =
      test::RunCommand(run + " " + dir.parent_path().string() + " --out " +
                           (test::MakeTempDir("swlio_bag_noimu") / "x").string() + " 2>&1",
                       &code);
  EXPECT_EQ(code, 1) << log;
  EXPECT_NE(log.find("no sensor_msgs/Imu topic (name one with --imu-topic)"), std::string::npos)
      << log;
}

}  // namespace
}  // namespace swlio
