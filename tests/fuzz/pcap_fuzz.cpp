// libFuzzer target: the pcap/pcapng reader on arbitrary file bytes (through fmemopen), reading
// every datagram. Invariant: each payload lies inside the record libpcap handed out (ASan
// checks the reads), and the reader stops.
// Seeds: python3 tests/fuzz/make_seeds.py <data dir> <out dir> (real capture, cut short).

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "swlio/drivers/pcap_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::vector<uint8_t> copy(data, data + size);  // fmemopen wants a mutable buffer
  FILE* stream = fmemopen(copy.data(), copy.size(), "rb");
  std::string error;
  auto reader = swlio::drivers::PcapReader::OpenStream(stream, {}, &error);
  if (!reader) return 0;
  swlio::drivers::UdpDatagram d;
  uint64_t sum = 0;
  while (reader->Next(&d)) {
    for (const uint8_t b : d.payload) sum += b;
  }
  if (reader->stats().returned > reader->stats().records) __builtin_trap();
  volatile uint64_t sink = sum;  // keep the payload reads
  (void)sink;
  return 0;
}
