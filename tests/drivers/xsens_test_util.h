#pragma once
// Helpers shared by the Xsens tests: file reading and "run bytes through the framer".

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <string>
#include <vector>

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
