#pragma once
// Helpers shared by the Xsens tests: file reading and "run bytes through the framer".

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <vector>

#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"

namespace swlio::test {

inline std::vector<uint8_t> ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The MTData2 payload of a level sample: PacketCounter `counter`, SampleTimeFine 25 ticks
/// (2.5 ms at 10 kHz) per count, gravity on z and a small rotation rate.
inline std::vector<uint8_t> LevelSamplePayload(uint16_t counter) {
  drivers::xsens::MtData2Sample s;
  s.packet_counter = counter;
  s.sample_time_fine = counter * 25u;
  const double acc[] = {0.0, 0.0, 9.81};
  const double gyro[] = {0.01, 0.02, 0.03};
  s.acc_mps2 = drivers::xsens::MakeXsensReal(acc);
  s.rate_of_turn_radps = drivers::xsens::MakeXsensReal(gyro);
  std::vector<uint8_t> payload(256);
  payload.resize(drivers::xsens::EncodeMtData2(s, payload));
  return payload;
}

struct OwnedFrame {
  uint8_t mid = 0;
  std::vector<uint8_t> payload;
  std::vector<uint8_t> wire;  ///< the whole frame as delivered
};

/// Feeds `bytes` in chunks of `chunk` bytes (1 = byte by byte) and collects every frame.
inline std::vector<OwnedFrame> CollectFrames(std::span<const uint8_t> bytes,
                                             size_t chunk,
                                             drivers::xsens::XbusFramerStats* stats = nullptr) {
  drivers::xsens::XbusFramer framer;
  std::vector<OwnedFrame> frames;
  size_t pos = 0;
  auto drain = [&] {
    drivers::xsens::XbusFrame f;
    while (framer.Next(&f)) {
      const uint8_t* start = f.payload.data() - (f.frame_bytes - 1 - f.payload.size());
      frames.push_back(
          {f.mid, {f.payload.begin(), f.payload.end()}, {start, start + f.frame_bytes}});
    }
  };
  while (pos < bytes.size()) {
    const size_t n = std::min(chunk, bytes.size() - pos);
    pos += framer.Feed(bytes.subspan(pos, n));
    drain();
  }
  framer.Flush();
  if (stats != nullptr) *stats = framer.stats();
  return frames;
}

}  // namespace swlio::test
