// swlio-run as a user runs it: a simulated recording in, a TUM trajectory and the stage timings
// CSV out; both the LiDAR-only odometry and the tightly coupled window (the default) follow the
// simulator's ground truth.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "scenarios/sim_setup.h"
#include "shared_sim_recording.h"
#include "state_nees.h"
#include "swlio/eval/evaluate.h"
#include "test_data.h"

namespace swlio {
namespace {

namespace fs = std::filesystem;

size_t CountLines(const fs::path& path, std::string* first) {
  std::ifstream in(path);
  std::string line;
  size_t n = 0;
  while (std::getline(in, line)) {
    if (n == 0 && first != nullptr) *first = line;
    ++n;
  }
  return n;
}

/// The number after the first `key` in `out` (NaN if none).
double NumberAfterKey(const std::string& out, const std::string& key) {
  const size_t at = out.find(key);
  return at == std::string::npos ? std::nan("") : std::stod(out.substr(at + key.size()));
}

/// 25 s of `short`: about 3 s standing (initialization), then ~25 m along the south road;
/// recorded once for the tests on it.
class RunOnShortDrive : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    std::string error;
    dir_ = new fs::path(test::SharedSimRecording("short", 11, 25.0, &error));
    out_ = new fs::path(test::MakeTempDir("swlio_run"));
    recorded_ = !dir_->empty();
  }
  static void TearDownTestSuite() {
    delete dir_;
    delete out_;
    dir_ = out_ = nullptr;
  }
  void SetUp() override {
    tool_ = test::ToolPath("swlio-run");
    if (tool_.empty()) GTEST_SKIP() << "swlio-run not built next to the tests";
    ASSERT_TRUE(recorded_);
  }
  static eval::Evaluation Ape(const fs::path& est) {
    eval::ApeOptions options;
    options.alignment = eval::Alignment::kSe3;
    return eval::EvaluateApe(eval::LoadPaired(*dir_ / "groundtruth.tum", est, eval::Format::kTum),
                             options);
  }

  static inline fs::path* dir_ = nullptr;  ///< the shared recording (read only)
  static inline fs::path* out_ = nullptr;  ///< this process's outputs
  static inline bool recorded_ = false;
  fs::path tool_;
};

TEST_F(RunOnShortDrive, LidarOnlyFollowsTheSimulatedDrive) {
  const fs::path& tool = tool_;
  const fs::path dir = *out_ / "lidar-only";
  fs::create_directories(dir);

  int code = 0;
  const std::string out =
      test::RunCommand(tool.string() + " " + dir_->string() + " --mode lidar-only --out " +
                           (dir / "est.tum").string() + " --timings " + (dir / "t.csv").string() +
                           " --diagnostics " + (dir / "d.csv").string() + " 2>&1",
                       &code);
  ASSERT_EQ(code, 0) << out;
  std::string header;
  const size_t timing_lines = CountLines(dir / "t.csv", &header);
  EXPECT_EQ(header, "t_ns,points,frontend_ms,match_ms,optimize_ms,total_ms,map_ms");
  EXPECT_GE(timing_lines, 240u);  // one per sweep (10 Hz) plus the header
  EXPECT_GE(CountLines(dir / "est.tum", nullptr), 200u);
  EXPECT_EQ(CountLines(dir / "d.csv", &header), timing_lines);
  EXPECT_EQ(header.rfind("t_ns,status,converged,iterations,", 0), 0u) << header;
  std::ifstream diag(dir / "d.csv");
  std::string line;
  size_t tracking = 0, initializing = 0;
  while (std::getline(diag, line)) {
    tracking += line.find(",tracking,1,") != std::string::npos ? 1 : 0;  // converged
    initializing += line.find(",initializing,") != std::string::npos ? 1 : 0;
  }
  EXPECT_GE(initializing, 1u) << "the drive starts standing";
  EXPECT_GE(tracking, 180u);

  const eval::Evaluation ape = Ape(dir / "est.tum");
  EXPECT_GE(ape.errors.size(), 200u);
  EXPECT_LT(ape.stats.rmse, 0.10) << out;  // measured 0.02 m; drift would grow past this
  EXPECT_LT(ape.stats.max, 0.25) << out;
}

TEST_F(RunOnShortDrive, TightlyCoupledFollowsTheSimulatedDrive) {
  const fs::path& tool = tool_;
  const fs::path dir = *out_ / "tightly-coupled";
  fs::create_directories(dir);
  int code = 0;
  // No --mode: tightly coupled is the default.
  const std::string out =
      test::RunCommand(tool.string() + " " + dir_->string() + " --out " +
                           (dir / "est.tum").string() + " --timings " + (dir / "t.csv").string() +
                           " --covariance " + (dir / "cov.csv").string() + " 2>&1",
                       &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("\"clock_jumps\": {\"lidar\": 0, \"imu\": 0}"), std::string::npos) << out;
  EXPECT_EQ(out.find("clock jumped"), std::string::npos) << out;
  // The recording has no time offset beyond the clock models' fraction of a millisecond: the
  // online estimate (on by default) must not invent one on this mostly straight drive.
  EXPECT_LT(std::abs(NumberAfterKey(out, "\"applied_ms\": ")), 1.0) << out;
  std::ifstream csv(dir / "t.csv");
  std::string line;
  size_t optimized = 0;
  std::getline(csv, line);
  while (std::getline(csv, line)) {
    double f = 0, m = 0, o = 0, tot = 0;
    long long t_ns = 0;
    size_t points = 0;
    if (std::sscanf(line.c_str(), "%lld,%zu,%lf,%lf,%lf,%lf", &t_ns, &points, &f, &m, &o, &tot) ==
            6 &&
        o > 0.0) {
      ++optimized;
    }
  }
  EXPECT_GE(optimized, 200u) << "the window optimization runs on every tracked sweep";

  const eval::Evaluation ape = Ape(dir / "est.tum");
  EXPECT_GE(ape.errors.size(), 200u);
  // LiDAR-only measures 0.02 m here (run_command_test.cpp); the window must not be worse.
  EXPECT_LT(ape.stats.rmse, 0.05) << out;
  EXPECT_LT(ape.stats.max, 0.15) << out;

  // The covariance where the window observes the state (state_nees.h): mean NEES of the tilt
  // (2 dof) and of the IMU-frame velocity (3 dof) within [¼, 3]× their dof. The tilt was 2×
  // overconfident when first measured and is about 1.5× with the gravity-tilt estimate
  // (docs/notes/2026-11-22-covariance-and-nees.md).
  const test::NeesSummary nees = test::StateNees(*dir_ / "groundtruth.tum", dir / "cov.csv", 1.0);
  std::cout << "[ nees ] tilt " << nees.tilt_mean << " (2 dof), velocity " << nees.velocity_mean
            << " (3 dof), " << nees.samples << " sweeps\n";
  EXPECT_GE(nees.samples, 200u);
  EXPECT_GT(nees.tilt_mean, 0.5);
  EXPECT_LT(nees.tilt_mean, 6.0);
  EXPECT_GT(nees.velocity_mean, 0.75);
  EXPECT_LT(nees.velocity_mean, 9.0);
}

// Started 12 s into the drive, at speed: the window starts from the LiDAR-IMU alignment
// (DynamicBootstrap), not from a "standing" IMU, so its first state already moves.
TEST_F(RunOnShortDrive, TightlyCoupledStartsWhileMoving) {
  const fs::path dir = *out_ / "moving-start";
  fs::create_directories(dir);
  int code = 0;
  const std::string out = test::RunCommand(
      tool_.string() + " " + dir_->string() + " --start-s 12 --out " + (dir / "est.tum").string() +
          " --diagnostics " + (dir / "d.csv").string() + " 2>&1",
      &code);
  ASSERT_EQ(code, 0) << out;
  std::ifstream diag(dir / "d.csv");
  std::string line;
  std::getline(diag, line);
  double first_speed = -1.0;
  size_t initializing = 0;
  while (std::getline(diag, line) && first_speed < 0.0) {
    if (line.find(",initializing,") != std::string::npos) {
      ++initializing;
      continue;
    }
    // vel_x,vel_y,vel_z are the 14th–16th columns.
    std::vector<double> v;
    size_t pos = 0;
    for (int col = 0; col < 16 && pos != std::string::npos; ++col) {
      const size_t next = line.find(',', pos);
      if (col >= 13) v.push_back(std::stod(line.substr(pos, next - pos)));
      pos = next == std::string::npos ? next : next + 1;
    }
    ASSERT_EQ(v.size(), 3u) << line;
    first_speed = std::hypot(v[0], v[1], v[2]);
  }
  EXPECT_GE(initializing, 10u) << "about 2 s of sweeps for the alignment";
  EXPECT_LE(initializing, 40u) << out;
  EXPECT_GT(first_speed, 0.8) << "the simulated robot drives at 1.2 m/s here";
  const eval::Evaluation ape = Ape(dir / "est.tum");
  EXPECT_GE(ape.errors.size(), 60u);
  EXPECT_LT(ape.stats.rmse, 0.10) << out;
}

// --calibrate-extrinsic on a drive without turns: the online calibration is tried, refused
// with its reason, and the run goes on with the given extrinsic (the truth here).
TEST_F(RunOnShortDrive, ExtrinsicCalibrationRefusesAStraightDrive) {
  const fs::path est = *out_ / "calibrate.tum";
  int code = 0;
  const std::string out = test::RunCommand(tool_.string() + " " + dir_->string() + " --out " +
                                               est.string() + " --calibrate-extrinsic 10 2>&1",
                                           &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("\"extrinsic_calibration\": {\"ok\": false, \"attempts\": "),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("it needs turns"), std::string::npos) << out;
  EXPECT_NE(out.find("\"from_given_rotation_deg\": 0.000"), std::string::npos) << out;
  EXPECT_LT(Ape(est).stats.rmse, 0.10) << out;
}

// --config's estimator.window reaches the window (estimate_extrinsic: the estimated extrinsic is
// printed at the end), a window flag given on the command line wins over the file, and an invalid
// file value is reported with its place.
TEST_F(RunOnShortDrive, ConfigWindowSectionAppliesAndFlagsOverride) {
  const fs::path dir = *out_ / "config";
  fs::create_directories(dir);
  std::ofstream(dir / "w.yaml") << "config_version: 1\nestimator:\n  window:\n    window_size: 7\n"
                                   "    estimate_extrinsic: true\n";
  std::ofstream(dir / "bad.yaml")
      << "config_version: 1\nestimator:\n  window:\n    lidar_sigma_m: -1\n";
  const std::string run =
      tool_.string() + " " + dir_->string() + " --out " + (dir / "est.tum").string() + " --config ";
  int code = 0;
  std::string out = test::RunCommand(run + (dir / "w.yaml").string() + " 2>&1", &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("\"extrinsic_T_imu_lidar\""), std::string::npos) << out;

  out = test::RunCommand(run + (dir / "w.yaml").string() + " --window-size 1 2>&1", &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(out.find("swlio-run: window_size: must be in [2, 50], got 1"), std::string::npos)
      << out;

  out = test::RunCommand(run + (dir / "bad.yaml").string() + " 2>&1", &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(out.find("bad.yaml:4:5: estimator.window.lidar_sigma_m: must be > 0, got -1"),
            std::string::npos)
      << out;
}

// --loop-closure on: along one road no place is seen twice, so no loop is tried and
// the published and final-graph trajectories are the plain odometry's; the summary counts the
// nodes. The switch in the configuration does the same (on by default); lidar-only mode
// refuses it. Then the graph saved as a map, and the same stretch localized in it.
TEST_F(RunOnShortDrive, LoopClosureWritesItsOutputsAndLeavesAStraightDriveAlone) {
  const fs::path dir = *out_ / "loops";
  fs::create_directories(dir);
  // The first 12 s (3 s standing, then ~9 m): enough for nodes, short under the sanitizers.
  const std::string run = tool_.string() + " " + dir_->string() + " --end-s 12 --out ";
  int code = 0;
  std::string out = test::RunCommand(
      run + (dir / "plain.tum").string() + " --loop-closure off 2>/dev/null", &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_EQ(out.find("\"loops\""), std::string::npos) << out;
  out = test::RunCommand(run + (dir / "default.tum").string() + " 2>/dev/null", &code);
  EXPECT_NE(out.find("\"loops\""), std::string::npos) << "on by default: " << out;
  out = test::RunCommand(run + (dir / "online.tum").string() +
                             " --loop-closure on --out-optimized " + (dir / "opt.tum").string() +
                             " --out-path " + (dir / "path.tum").string() + " --loops " +
                             (dir / "l.csv").string() + " 2>/dev/null",
                         &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("\"attempts\": 0, \"accepted\": 0"), std::string::npos) << out;
  const double nodes = NumberAfterKey(out, "\"nodes\": ");
  EXPECT_GE(nodes, 5.0) << out;  // ~9 m at one node per metre
  const auto slurp = [](const fs::path& p) {
    std::ifstream f(p);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  const std::string plain = slurp(dir / "plain.tum");
  EXPECT_GT(plain.size(), 5000u);
  EXPECT_EQ(slurp(dir / "online.tum"), plain);
  const std::string optimized = slurp(dir / "opt.tum");
  EXPECT_EQ(optimized.substr(optimized.find('\n')), plain.substr(plain.find('\n')))
      << "the same poses (the header line differs)";
  // The path: one line per node, each one of the sweeps' own lines (no loop moved them).
  std::ifstream path(dir / "path.tum");
  std::string line;
  size_t path_nodes = 0;
  std::getline(path, line);
  EXPECT_EQ(line.rfind("# timestamp", 0), 0u) << line;
  while (std::getline(path, line)) {
    ++path_nodes;
    EXPECT_NE(plain.find(line + "\n"), std::string::npos) << "not a sweep's pose: " << line;
  }
  EXPECT_EQ(static_cast<double>(path_nodes), nodes);
  out = test::RunCommand(run + (dir / "x.tum").string() + " --loop-closure off --out-path " +
                             (dir / "x_path.tum").string() + " 2>&1",
                         &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(out.find("need loop closure"), std::string::npos) << out;
  std::string header;
  EXPECT_EQ(CountLines(dir / "l.csv", &header), 1u);
  EXPECT_EQ(header.rfind("candidate_t_ns,node_t_ns,distance_m,verdict,", 0), 0u) << header;

  std::ofstream(dir / "on.yaml") << "config_version: 1\nestimator:\n  loop_closure:\n"
                                    "    enabled: true\n";
  out = test::RunCommand(
      run + (dir / "c.tum").string() + " --config " + (dir / "on.yaml").string() + " 2>/dev/null",
      &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("\"loops\""), std::string::npos) << out;
  out = test::RunCommand(run + (dir / "c.tum").string() + " --config " +
                             (dir / "on.yaml").string() + " --loop-closure off 2>/dev/null",
                         &code);
  EXPECT_EQ(out.find("\"loops\""), std::string::npos) << out;
  out = test::RunCommand(
      run + (dir / "c.tum").string() + " --mode lidar-only --loop-closure on 2>&1", &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(out.find("--loop-closure on needs --mode tightly-coupled"), std::string::npos) << out;

  const std::string map = (dir / "map.swlmap").string();
  out = test::RunCommand(run + (dir / "m.tum").string() + " --save-map " + map + " --map-pcd " +
                             (dir / "map.pcd").string() + " 2>/dev/null",
                         &code);
  ASSERT_EQ(code, 0) << out;
  std::ifstream pcd(dir / "map.pcd");
  std::string first_line;
  std::getline(pcd, first_line);
  EXPECT_EQ(first_line.rfind("# .PCD v0.7", 0), 0u) << first_line;
  out = test::RunCommand(
      run + (dir / "loc.tum").string() + " --map " + map + " --localize 2>/dev/null", &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("\"state\": \"tracking\""), std::string::npos) << out;
  const double after_s = NumberAfterKey(out, "\"localized_after_s\": ");
  EXPECT_GE(after_s, 0.0) << out;
  EXPECT_LT(after_s, 5.0) << out;
  EXPECT_GT(CountLines(dir / "loc.tum", &header), 10u);
  std::ofstream(dir / "bad.swlmap") << "SWLIOMAP but not a map";
  out = test::RunCommand(run + (dir / "bad.tum").string() + " --map " +
                             (dir / "bad.swlmap").string() + " --localize 2>&1",
                         &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(out.find("map file"), std::string::npos) << out;
}

// Wheel odometry (the recording's can.log, differential drive with the simulator's wheel-radius
// errors) as the window's velocity factor: every tracked sweep gets one and the drive is
// followed as well as without, within 20 % (on 25 m the LiDAR alone is at 1.4 cm; the wheels
// pay off on long drives: docs/notes/2026-11-24-wheel-odometry-and-gnss.md).
TEST_F(RunOnShortDrive, WheelOdometryFactorOnEverySweep) {
  const fs::path dir = *out_ / "wheel";
  fs::create_directories(dir);
  const std::string run = tool_.string() + " " + dir_->string() + " --loop-closure off --out ";
  int code = 0;
  std::string out = test::RunCommand(run + (dir / "off.tum").string() + " 2>/dev/null", &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_EQ(out.find("\"wheel\""), std::string::npos) << "off by default: " << out;
  out = test::RunCommand(run + (dir / "on.tum").string() + " --wheel on 2>/dev/null", &code);
  ASSERT_EQ(code, 0) << out;
  const double factors = NumberAfterKey(out, "\"factors\": ");
  EXPECT_GE(factors, 200.0) << out;
  EXPECT_EQ(NumberAfterKey(out, "\"rejected\": "), 0.0) << out;
  const double off = Ape(dir / "off.tum").stats.rmse, on = Ape(dir / "on.tum").stats.rmse;
  std::cout << "[ wheel ] APE RMSE off " << off << " m, on " << on << " m\n";
  EXPECT_LT(on, 1.2 * off + 0.002);
  EXPECT_LT(on, 0.05);
}

// GNSS (GnssPvtData in imu.xbus, Gauss-Markov errors of σ 0.8 m horizontal / 1.5 m vertical):
// with --gnss on the graph runs without loop detection, aligns its map frame to the local ENU
// frame once the fixes span 20 m, and --out-enu is georeferenced: compared to the truth (the
// simulator's world is that ENU frame) with no alignment at all, its error is the receiver's.
TEST_F(RunOnShortDrive, GnssGeoreferencesTheTrajectory) {
  const fs::path dir = *out_ / "gnss";
  fs::create_directories(dir);
  int code = 0;
  const std::string out =
      test::RunCommand(tool_.string() + " " + dir_->string() +
                           " --loop-closure off --gnss on --out " + (dir / "online.tum").string() +
                           " --out-enu " + (dir / "enu.tum").string() + " 2>/dev/null",
                       &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("\"aligned\": true"), std::string::npos) << out;
  EXPECT_EQ(NumberAfterKey(out, "\"attempts\": "), 0.0) << "no loop detection: " << out;
  EXPECT_GE(NumberAfterKey(out, "\"edges\": "), 15.0) << out;
  eval::ApeOptions none;
  none.alignment = eval::Alignment::kNone;
  const eval::Evaluation geo = eval::EvaluateApe(
      eval::LoadPaired(*dir_ / "groundtruth.tum", dir / "enu.tum", eval::Format::kTum), none);
  std::cout << "[ gnss ] georeferenced APE RMSE (no alignment) " << geo.stats.rmse << " m\n";
  EXPECT_GE(geo.errors.size(), 200u);
  EXPECT_LT(geo.stats.rmse, 3.0);
  // Without GNSS the odometry's frame is its start's: no alignment leaves it far off.
  const eval::Evaluation odom = eval::EvaluateApe(
      eval::LoadPaired(*dir_ / "groundtruth.tum", dir / "online.tum", eval::Format::kTum), none);
  EXPECT_GT(odom.stats.rmse, geo.stats.rmse);
  // The local shape stays the odometry's.
  EXPECT_LT(Ape(dir / "enu.tum").stats.rmse, 0.1);
}

/// The number after `key` in `out`'s last line that has it (NaN if none).
double LastNumberAfter(const std::string& out, const std::string& key) {
  const size_t at = out.rfind(key);
  return at == std::string::npos ? std::nan("") : std::stod(out.substr(at + key.size()));
}

// The online extrinsic calibration on 33 s of the `aggressive` drive (turns from 8 s on), started
// 2° and 5 cm (horizontal) off: after 30 s of LiDAR-only odometry beside the window the batch
// is accepted and the window restarts on it (docs/notes/2026-11-22-online-extrinsic.md).
TEST(RunOnAggressiveDrive, OnlineCalibrationRecoversTheExtrinsic) {
  const fs::path tool = test::ToolPath("swlio-run");
  if (tool.empty()) GTEST_SKIP() << "swlio-run not built next to the tests";
  const fs::path dir = test::MakeTempDir("swlio_run_calibrate");
  auto setup = sim::MakeSimSetup("aggressive", 1, 33.0);
  sim::RecordingStats stats;
  std::string error;
  ASSERT_TRUE(setup && sim::WriteRecording(*setup, dir, &stats, &error)) << error;
  int code = 0;
  const std::string out = test::RunCommand(
      tool.string() + " " + dir.string() + " --out " + (dir / "est.tum").string() +
          " --calibrate-extrinsic 30 --extrinsic-offset 0.035 0.035 0 1.155 1.155 1.155 2>&1",
      &code);
  ASSERT_EQ(code, 0) << out;
  ASSERT_NE(out.find("\"extrinsic_calibration\": {\"ok\": true"), std::string::npos) << out;
  // The extrinsic the window ends with (the run's last line) against the truth: 2.0° and 4.9 cm
  // before; measured 0.27° and 0.8 cm.
  EXPECT_LT(LastNumberAfter(out, "\"from_given_rotation_deg\": "), 0.5) << out;
  EXPECT_LT(LastNumberAfter(out, "\"from_given_translation_m\": "), 0.02) << out;
}

// The LiDAR's clock set anew mid-drive (GPS time arriving): the run says so, since the sweeps
// around the step are mis-timed and a divergence would otherwise be the only sign.
TEST(RunCommand, SaysThatASensorClockJumped) {
  const fs::path tool = test::ToolPath("swlio-run");
  if (tool.empty()) GTEST_SKIP() << "swlio-run not built next to the tests";
  const fs::path dir = test::MakeTempDir("swlio_run_clock_jump");
  auto setup = sim::MakeSimSetup("short", 12, 6.0);
  ASSERT_TRUE(setup);
  setup->lidar.clock.step_at_s = 4.0;
  setup->lidar.clock.step_s = 3600.0;
  sim::RecordingStats stats;
  std::string error;
  ASSERT_TRUE(sim::WriteRecording(*setup, dir, &stats, &error)) << error;
  int code = 0;
  const std::string out = test::RunCommand(
      tool.string() + " " + dir.string() + " --out " + (dir / "est.tum").string() + " 2>&1", &code);
  ASSERT_EQ(code, 0) << out;
  EXPECT_NE(out.find("the LiDAR clock jumped 1 time(s)"), std::string::npos) << out;
  EXPECT_NE(out.find("\"clock_jumps\": {\"lidar\": 1, \"imu\": 0}"), std::string::npos) << out;
}

TEST(RunCommand, MissingFolderIsAClearError) {
  const fs::path tool = test::ToolPath("swlio-run");
  if (tool.empty()) GTEST_SKIP() << "swlio-run not built next to the tests";
  int code = 0;
  const std::string out =
      test::RunCommand(tool.string() + " /nonexistent/rec --out /dev/null 2>&1", &code);
  EXPECT_NE(code, 0);
  EXPECT_NE(out.find("/nonexistent/rec"), std::string::npos) << out;
}

}  // namespace
}  // namespace swlio
