// CAN decode throughput: wheel-odometry frames/s through WheelOdomDecoder (differential layout,
// both wheels in one frame, plus one frame in four from an unrelated id), and candump lines/s
// through ParseCandumpLine.

#include <benchmark/benchmark.h>

#include <array>
#include <string>
#include <vector>

#include "swlio/drivers/candump_log.h"
#include "swlio/drivers/wheel_odom_decoder.h"

namespace swlio::drivers {
namespace {

std::vector<CanFrame> MakeFrames() {
  std::vector<CanFrame> frames(1024);
  for (size_t i = 0; i < frames.size(); ++i) {
    CanFrame& f = frames[i];
    f.id = i % 4 == 3 ? 0x300 : 0x201;
    f.dlc = 8;
    for (size_t k = 0; k < 8; ++k) f.data[k] = static_cast<uint8_t>(i * 31 + k * 7);
  }
  return frames;
}

CanConfig Layout(const char* order) {
  CanConfig c;
  for (const char* role : {"left_wheel_speed", "right_wheel_speed"}) {
    CanSignalConfig s;
    s.role = role;
    s.can_id = 0x201;
    s.byte_offset = c.signals.empty() ? 0 : 2;
    s.length_bits = 16;
    s.byte_order = order;
    s.scale = 0.001;
    c.signals.push_back(s);
  }
  return c;
}

void DecodeFrames(benchmark::State& state, const char* order) {
  const std::vector<CanFrame> frames = MakeFrames();
  auto decoder = WheelOdomDecoder::Create(Layout(order));
  if (!decoder) {
    state.SkipWithError("invalid layout");
    return;
  }
  int64_t t_ns = 0;
  double sum = 0.0;
  for (auto _ : state) {
    for (const CanFrame& f : frames) {
      const auto s = decoder->Decode(f, t_ns++);
      if (s) sum += s->linear_velocity_mps;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(frames.size()));
  state.counters["frames_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * static_cast<int64_t>(frames.size())),
      benchmark::Counter::kIsRate);
}

void BM_WheelOdomDecodeIntel(benchmark::State& state) { DecodeFrames(state, "intel"); }
void BM_WheelOdomDecodeMotorola(benchmark::State& state) { DecodeFrames(state, "motorola"); }

void BM_CandumpParseLine(benchmark::State& state) {
  std::vector<std::string> lines;
  std::array<char, kCandumpMaxLineBytes> buf{};
  for (const CanFrame& f : MakeFrames()) {
    const size_t n =
        FormatCandumpLine(MakeCandumpRecord(1'700'000'000'000'000'000, "can0", f), buf);
    lines.emplace_back(buf.data(), n);
  }
  CandumpRecord r;
  for (auto _ : state) {
    for (const std::string& line : lines) {
      benchmark::DoNotOptimize(ParseCandumpLine(line, &r));
    }
  }
  state.counters["lines_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * static_cast<int64_t>(lines.size())),
      benchmark::Counter::kIsRate);
}

BENCHMARK(BM_WheelOdomDecodeIntel);
BENCHMARK(BM_WheelOdomDecodeMotorola);
BENCHMARK(BM_CandumpParseLine);

}  // namespace
}  // namespace swlio::drivers
