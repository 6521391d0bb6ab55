// Xbus framing + MTData2 decoding throughput on one core.
//
// "Typical 400 Hz frame": what ConfiguratorOptionsFromConfig asks for plus the delta items
// (PacketCounter, SampleTimeFine, StatusWord, Quaternion, Acceleration, RateOfTurn, DeltaV,
// DeltaQ in Float32; 109-byte frames). Also the real einride MTi-G-710 capture when present.
// Goal: ≥ 1,000,000 frames/s.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace xs = swlio::drivers::xsens;

namespace {

std::vector<uint8_t> TypicalStream(size_t frames) {
  std::vector<uint8_t> stream;
  for (size_t i = 0; i < frames; ++i) {
    const double d = static_cast<double>(i) * 1e-3;
    const double v3[] = {0.01 + d, -0.02, 9.81};
    const double q4[] = {1.0, d, 0.0, 0.0};
    xs::MtData2Sample s;
    s.packet_counter = static_cast<uint16_t>(i);
    s.sample_time_fine = static_cast<uint32_t>(i * 25);
    s.status_word = 0x3;
    s.quaternion = xs::MakeXsensReal(q4);
    s.acc_mps2 = xs::MakeXsensReal(v3);
    s.rate_of_turn_radps = xs::MakeXsensReal(v3);
    s.delta_v_mps = xs::MakeXsensReal(v3);
    s.delta_q = xs::MakeXsensReal(q4);
    std::array<uint8_t, 256> payload;
    const size_t n = xs::EncodeMtData2(s, payload);
    std::array<uint8_t, 300> frame;
    const size_t f = xs::EncodeXbusFrame(xs::mid::kMtData2, {payload.data(), n}, frame);
    stream.insert(stream.end(), frame.begin(), frame.begin() + static_cast<std::ptrdiff_t>(f));
  }
  return stream;
}

/// Frames and decodes `stream` in 4 KiB reads, as the serial shell would deliver it.
void FrameAndDecode(benchmark::State& state, const std::vector<uint8_t>& stream) {
  xs::XbusFramer framer;
  xs::MtData2Sample sample;
  xs::XbusFrame frame;
  uint64_t frames = 0;
  for (auto _ : state) {
    for (size_t pos = 0; pos < stream.size();) {
      const size_t n = std::min<size_t>(4096, stream.size() - pos);
      pos += framer.Feed({stream.data() + pos, n});
      while (framer.Next(&frame)) {
        xs::DecodeMtData2(frame.payload, &sample);
        benchmark::DoNotOptimize(sample);
        if (auto imu = xs::ToImuSample(sample, 0)) benchmark::DoNotOptimize(*imu);
        ++frames;
      }
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(frames));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * stream.size()));
  state.counters["frame_bytes"] = static_cast<double>(stream.size()) *
                                  static_cast<double>(state.iterations()) /
                                  static_cast<double>(frames > 0 ? frames : 1);
}

void BM_Typical400HzFrames(benchmark::State& state) {
  static const std::vector<uint8_t> stream = TypicalStream(4000);
  FrameAndDecode(state, stream);
}
BENCHMARK(BM_Typical400HzFrames);

void BM_EinrideCapture(benchmark::State& state) {
  const char* dir = std::getenv("SWLIO_DATA_DIR");
  const std::filesystem::path path =
      std::filesystem::path(dir != nullptr ? dir : "../shared/data") /
      "xsens_einride_mti-g-710/1/output.bin";
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    state.SkipWithError("einride capture not found (set SWLIO_DATA_DIR)");
    return;
  }
  const std::vector<uint8_t> stream{std::istreambuf_iterator<char>(in),
                                    std::istreambuf_iterator<char>()};
  FrameAndDecode(state, stream);
}
BENCHMARK(BM_EinrideCapture);

void BM_FramerOnly(benchmark::State& state) {
  static const std::vector<uint8_t> stream = TypicalStream(4000);
  xs::XbusFramer framer;
  xs::XbusFrame frame;
  uint64_t frames = 0;
  for (auto _ : state) {
    for (size_t pos = 0; pos < stream.size();) {
      pos += framer.Feed({stream.data() + pos, std::min<size_t>(4096, stream.size() - pos)});
      while (framer.Next(&frame)) ++frames;
    }
  }
  state.SetItemsProcessed(static_cast<int64_t>(frames));
}
BENCHMARK(BM_FramerOnly);

}  // namespace
