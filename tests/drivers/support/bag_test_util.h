#pragma once
/// @file
/// Helpers shared by the bag tests: reading a whole bag into owned messages, and the UDP
/// payloads of a capture.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "swlio/drivers/bag/bag_reader.h"
#include "swlio/drivers/pcap_file.h"

namespace swlio::test {

struct OwnedMessage {
  uint32_t topic = 0;
  uint64_t index = 0;
  int64_t log_time_ns = 0;
  std::vector<uint8_t> data;
  bool operator==(const OwnedMessage&) const = default;
};

inline std::vector<OwnedMessage> ReadAll(drivers::bag::BagReader& reader) {
  std::vector<OwnedMessage> out;
  drivers::bag::BagMessage m;
  while (reader.Next(&m)) {
    out.push_back({m.topic, m.index, m.log_time_ns, {m.data.begin(), m.data.end()}});
  }
  return out;
}

struct Payload {
  uint16_t dst_port = 0;
  int64_t t_ns = 0;
  std::vector<uint8_t> bytes;
};

inline std::vector<Payload> PcapPayloads(const std::filesystem::path& path) {
  std::vector<Payload> out;
  std::string error;
  auto reader = drivers::PcapReader::Open(path.string(), {}, &error);
  EXPECT_NE(reader, nullptr) << error;
  drivers::UdpDatagram d;
  while (reader && reader->Next(&d)) {
    out.push_back({d.dst_port, d.t_ns, {d.payload.begin(), d.payload.end()}});
  }
  return out;
}

}  // namespace swlio::test
