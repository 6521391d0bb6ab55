// ROS bag reading throughput on one core (issue 32: "a 10-minute bag is read faster than 20×
// real time"): messages/s and MB/s of the bag readers, of the decoded message stream
// (BagMessageStream: reading, decoding, stamp checks), and of the whole input of swlio-run
// (BagInput: the stream, then the packets through the daemon's LiDAR decoder, clock model and
// scan assembler, events ordered by time).
//
// Input: a synthetic recording of SWLIO_BAG_BENCH_SECONDS (default 60) of an RS16 and an IMU at
// the rates of the target rig — 10 RslidarScan messages/s of 75 packets (94 KB each, the
// washing_house layout; payloads cycled from the real bag when found under $SWLIO_DATA_DIR or
// ../shared/data) and 400 sensor_msgs/Imu/s — written once into /tmp as rosbag2 .db3, MCAP
// (none, zstd, lz4 chunks) and a ROS 1 bag (lz4). `real_time_factor` = recorded seconds per
// second of reading; throughput does not depend on the length, so 60 s stands for 10 minutes
// (SWLIO_BAG_BENCH_SECONDS=600 measures one directly, ~0.6 GB per format in /tmp).
// The real washing_house bag (3.9 s) is read as well.

#include <benchmark/benchmark.h>
#include <sqlite3.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ros1_bag_writer.h"  // tests/drivers/support
#include "swlio/daemon/recording/bag_input.h"
#include "swlio/drivers/bag/bag_message_stream.h"
#include "swlio/drivers/bag/bag_open.h"
#include "swlio/drivers/bag/mcap_writer.h"
#include "swlio/drivers/bag/message_encoder.h"

namespace {

namespace fs = std::filesystem;
namespace bag = swlio::drivers::bag;
using Bytes = std::vector<uint8_t>;

constexpr int64_t kT0 = 1'660'622'130'000'000'000;
constexpr int64_t kScanPeriodNs = 100'000'000;  // 10 Hz
constexpr int64_t kImuPeriodNs = 2'500'000;     // 400 Hz
constexpr size_t kPacketsPerScan = 75;

fs::path DataDir() {
  const char* env = std::getenv("SWLIO_DATA_DIR");  // NOLINT(concurrency-mt-unsafe)
  return env != nullptr ? fs::path(env) : fs::path("../shared/data");
}

int64_t BenchSeconds() {
  const char* env = std::getenv("SWLIO_BAG_BENCH_SECONDS");  // NOLINT(concurrency-mt-unsafe)
  return env != nullptr ? std::max(1L, std::atol(env)) : 60;
}

/// 1248-byte MSOP payloads: the real bag's when present, else a fixed synthetic pattern.
std::vector<Bytes> Payloads() {
  std::vector<Bytes> out;
  std::string error;
  const fs::path real = DataDir() / "rs16_washing_house/rosbag2_2022_08_16-11_55_30_0.db3";
  if (auto r = bag::OpenBag(real.string(), {}, &error)) {
    bag::BagMessage m;
    bag::DecodedMessage d;
    while (r->Next(&m) && out.size() < 750) {
      const bag::BagTopic& t = r->topics()[m.topic];
      if (!bag::DecodeMessage(bag::ClassifyTopic(t), t.encoding, m.data, &d, &error)) continue;
      if (d.kind != bag::RosMessageKind::kRslidarScan) continue;
      for (const auto& p : d.packets.packets) out.emplace_back(p.payload.begin(), p.payload.end());
    }
  }
  if (out.empty()) out.assign(kPacketsPerScan, Bytes(1248, 0x5A));
  return out;
}

/// One recorded message of the synthetic rig.
struct Recorded {
  bool lidar;
  int64_t t_ns;
  Bytes cdr;
  Bytes ros1;
};

/// The rig's messages in time order, built on demand one at a time.
template <typename F>
void ForEachMessage(F&& f) {
  static const std::vector<Bytes> payloads = Payloads();
  const int64_t end = kT0 + BenchSeconds() * 1'000'000'000;
  int64_t next_scan = kT0 + kScanPeriodNs;
  size_t k = 0;
  for (int64_t t = kT0; t < end; t += kImuPeriodNs) {
    bag::ImuMsg imu;
    imu.header = {t - 300'000, "imu_link"};
    imu.linear_acceleration_mps2 = {0.0, 0.0, 9.81};
    f(Recorded{false, t, bag::EncodeImu(imu, bag::MessageEncoding::kCdr),
               bag::EncodeImu(imu, bag::MessageEncoding::kRos1)});
    if (t < next_scan) continue;
    bag::LidarPacketsMsg scan;
    scan.has_header = true;
    scan.header = {next_scan - 1'000'000, "/rslidar"};
    for (size_t i = 0; i < kPacketsPerScan; ++i) {
      scan.packets.push_back({0, payloads[k++ % payloads.size()], bag::PacketRole::kUnstated});
    }
    Recorded r{true, t, {}, {}};
    bag::EncodeLidarPackets(bag::RosMessageKind::kRslidarScan, scan, bag::MessageEncoding::kCdr,
                            &r.cdr);
    bag::EncodeLidarPackets(bag::RosMessageKind::kRslidarScan, scan, bag::MessageEncoding::kRos1,
                            &r.ros1);
    f(r);
    next_scan += kScanPeriodNs;
  }
}

void WriteDb3(const fs::path& path) {
  fs::remove(path);
  sqlite3* db = nullptr;
  sqlite3_open(path.c_str(), &db);
  sqlite3_exec(db,
               "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT "
               "NULL, serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
               "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
               "timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
               "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
               "INSERT INTO topics VALUES(1, '/imu/data', 'sensor_msgs/msg/Imu', 'cdr', '');"
               "INSERT INTO topics VALUES(2, '/rslidar_packets', 'rslidar_msg/msg/RslidarScan', "
               "'cdr', '');BEGIN",
               nullptr, nullptr, nullptr);
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(db, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", -1, &s,
                     nullptr);
  ForEachMessage([&](const Recorded& r) {
    sqlite3_bind_int64(s, 1, r.lidar ? 2 : 1);
    sqlite3_bind_int64(s, 2, r.t_ns);
    sqlite3_bind_blob(s, 3, r.cdr.data(), static_cast<int>(r.cdr.size()), SQLITE_STATIC);
    sqlite3_step(s);
    sqlite3_reset(s);
  });
  sqlite3_finalize(s);
  sqlite3_exec(db, "COMMIT", nullptr, nullptr, nullptr);
  sqlite3_close(db);
}

void WriteMcap(const fs::path& path, bag::Compression c) {
  bag::McapWriterOptions o;
  o.compression = c;
  std::string error;
  auto w = bag::McapWriter::Create(path.string(), o, &error);
  const uint16_t imu =
      w->AddChannel(w->AddSchema("sensor_msgs/msg/Imu", "ros2msg", ""), "/imu/data", "cdr");
  const uint16_t lidar = w->AddChannel(w->AddSchema("rslidar_msg/msg/RslidarScan", "ros2msg", ""),
                                       "/rslidar_packets", "cdr");
  ForEachMessage(
      [&](const Recorded& r) { w->Write(r.lidar ? lidar : imu, r.t_ns, r.t_ns, r.cdr); });
  w->Close(&error);
}

void WriteRos1(const fs::path& path) {
  swlio::test::Ros1BagWriter w("lz4", 768 * 1024);
  w.AddConnection({0, "/imu/data", "sensor_msgs/Imu", "6a62c6daae103f4ff57a132d6f95cec2", ""});
  w.AddConnection(
      {1, "/rslidar_packets", "rslidar_msgs/rslidarScan", "ff6baa58985b528481871cbaf1bb342f", ""});
  ForEachMessage([&](const Recorded& r) { w.Write(r.lidar ? 1 : 0, r.t_ns, r.ros1); });
  const Bytes b = w.Finish();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
}

/// The synthetic bag of format `index`, written on first use.
const std::string& SyntheticBag(size_t index) {
  static std::vector<std::string> paths(5);
  static const char* kNames[] = {"bag.db3", "none.mcap", "zstd.mcap", "lz4.mcap", "lz4.bag"};
  if (!paths[index].empty()) return paths[index];
  const fs::path dir =
      fs::temp_directory_path() / ("swlio_bag_bench_" + std::to_string(BenchSeconds()));
  fs::create_directories(dir);
  const fs::path p = dir / kNames[index];
  if (!fs::exists(p)) {
    if (index == 0) WriteDb3(p);
    if (index == 1) WriteMcap(p, bag::Compression::kNone);
    if (index == 2) WriteMcap(p, bag::Compression::kZstd);
    if (index == 3) WriteMcap(p, bag::Compression::kLz4Frame);
    if (index == 4) WriteRos1(p);
  }
  paths[index] = p.string();
  return paths[index];
}

void Report(benchmark::State& state, uint64_t messages, uint64_t bytes, double recorded_s) {
  state.counters["messages_per_s"] =
      benchmark::Counter(static_cast<double>(messages), benchmark::Counter::kIsRate);
  state.counters["MB_per_s"] =
      benchmark::Counter(static_cast<double>(bytes) / 1e6, benchmark::Counter::kIsRate);
  state.counters["real_time_factor"] = benchmark::Counter(recorded_s, benchmark::Counter::kIsRate);
}

/// Open + read every message (no decoding).
void BM_ReadBag(benchmark::State& state) {
  const std::string& path = SyntheticBag(static_cast<size_t>(state.range(0)));
  state.SetLabel(fs::path(path).filename().string());
  uint64_t messages = 0;
  uint64_t bytes = 0;
  for (auto _ : state) {
    std::string error;
    auto reader = bag::OpenBag(path, {}, &error);
    bag::BagMessage m;
    while (reader->Next(&m)) {
      ++messages;
      bytes += m.data.size();
      benchmark::DoNotOptimize(m.data.data());
    }
  }
  Report(state, messages, bytes, static_cast<double>(BenchSeconds() * state.iterations()));
}
BENCHMARK(BM_ReadBag)->DenseRange(0, 4)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The whole input path: open, read, decode, check stamps (BagMessageStream).
void BM_StreamBag(benchmark::State& state) {
  const std::string& path = SyntheticBag(static_cast<size_t>(state.range(0)));
  state.SetLabel(fs::path(path).filename().string());
  uint64_t messages = 0;
  uint64_t packets = 0;
  for (auto _ : state) {
    std::string error;
    auto stream = bag::BagMessageStream::Create(bag::OpenBag(path, {}, &error), {}, &error);
    bag::StreamMessage m;
    while (stream->Next(&m)) {
      ++messages;
      if (m.kind == bag::RosMessageKind::kRslidarScan) packets += m.decoded->packets.packets.size();
    }
  }
  // MB/s of LiDAR payload delivered.
  Report(state, messages, packets * 1248, static_cast<double>(BenchSeconds() * state.iterations()));
}
BENCHMARK(BM_StreamBag)->DenseRange(0, 4)->Unit(benchmark::kMillisecond)->UseRealTime();

/// swlio-run's input: sweeps and IMU samples on the host clock (BagInput).
void BM_BagInput(benchmark::State& state) {
  const std::string& path = SyntheticBag(static_cast<size_t>(state.range(0)));
  state.SetLabel(fs::path(path).filename().string());
  uint64_t events = 0;
  uint64_t points = 0;
  for (auto _ : state) {
    std::string error;
    auto input = swlio::daemon::OpenBagInput(path, {}, {}, &error);
    if (!input) {
      state.SkipWithError(error.c_str());
      return;
    }
    swlio::daemon::RecordingEvent e;
    while (input->Next(&e)) {
      ++events;
      points += e.scan.points.size();
      e.scan.points.clear();
    }
  }
  if (points == 0) {  // the synthetic fallback payloads are no valid MSOP packets
    state.SkipWithError("no sweeps: the real washing_house payloads are needed (SWLIO_DATA_DIR)");
    return;
  }
  state.counters["points_per_s"] =
      benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsRate);
  Report(state, events, 0, static_cast<double>(BenchSeconds() * state.iterations()));
}
BENCHMARK(BM_BagInput)->Arg(0)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The real washing_house bag (3.9 s, 80 messages, 3.8 MB) through the stream.
void BM_StreamWashingHouse(benchmark::State& state) {
  const fs::path path = DataDir() / "rs16_washing_house";
  std::string error;
  if (!bag::OpenBag(path.string(), {}, &error)) {
    state.SkipWithError(("no real bag: " + error).c_str());
    return;
  }
  uint64_t messages = 0;
  uint64_t bytes = 0;
  for (auto _ : state) {
    auto stream =
        bag::BagMessageStream::Create(bag::OpenBag(path.string(), {}, &error), {}, &error);
    bag::StreamMessage m;
    while (stream->Next(&m)) {
      ++messages;
      bytes += m.decoded->packets.packets.size() * 1248;  // every message here is LiDAR
    }
  }
  Report(state, messages, bytes, 3.903 * static_cast<double>(state.iterations()));
}
BENCHMARK(BM_StreamWashingHouse)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
