// libFuzzer target: arbitrary bytes through the Xbus framer (in input-chosen split sizes),
// every frame through the MTData2 decoder and re-encoder, and the configurator's frame
// handling; then the same bytes through the stream decoder, the device re-opened (a new epoch)
// at an input-chosen byte. Invariants checked: framer byte accounting (across the restart too),
// frame checksum, re-encode of a decoded payload never overflows and decodes again to the same
// item list.

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "swlio/drivers/xsens/configurator.h"
#include "swlio/drivers/xsens/mtdata2.h"
#include "swlio/drivers/xsens/xbus.h"
#include "swlio/drivers/xsens/xsens_stream_decoder.h"

namespace xs = swlio::drivers::xsens;

namespace {

void Check(bool ok) {
  if (!ok) std::abort();
}

void OnFrame(const xs::XbusFrame& frame, xs::XsensConfigurator* config, int64_t t_ns) {
  Check(frame.payload.size() <= xs::kXbusMaxPayload);
  config->OnFrame(frame, t_ns);
  config->OnTick(t_ns);
  if (frame.mid != xs::mid::kMtData2) return;
  static xs::MtData2Sample sample, again;
  const xs::MtData2Status status = xs::DecodeMtData2(frame.payload, &sample);
  static std::array<uint8_t, xs::kXbusMaxPayload + 64> out;
  const size_t n = xs::EncodeMtData2(sample, out);
  if (status != xs::MtData2Status::kOk || sample.item_count >= xs::MtData2Sample::kMaxItems) return;
  // The sample holds one value per type (the last one sent), so a message repeating a type
  // cannot round-trip; real devices never repeat one.
  for (size_t i = 0; i < sample.item_count; ++i) {
    for (size_t j = 0; j < i; ++j) {
      if ((sample.item_ids[i] & 0xFFF0) == (sample.item_ids[j] & 0xFFF0)) return;
    }
  }
  // Known items re-encode into at most the original size and decode to the same items.
  Check(n <= frame.payload.size());
  Check(xs::DecodeMtData2({out.data(), n}, &again) == xs::MtData2Status::kOk);
  Check(again.item_count == sample.item_count);
  for (size_t i = 0; i < sample.item_count; ++i) Check(again.item_ids[i] == sample.item_ids[i]);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static xs::XbusFramer framer;
  framer = xs::XbusFramer{};
  xs::XsensConfigurator config(xs::XsensConfiguratorOptions{});
  config.Start(0);
  // The first byte picks the read size, so split reads are explored too.
  const size_t chunk = size > 0 ? 1 + data[0] % 64 : 1;
  size_t pos = 0;
  int64_t t_ns = 0;
  xs::XbusFrame frame;
  while (pos < size) {
    const size_t n = chunk < size - pos ? chunk : size - pos;
    pos += framer.Feed({data + pos, n});
    while (framer.Next(&frame)) OnFrame(frame, &config, t_ns += 1'000'000);
  }
  framer.Flush();
  const xs::XbusFramerStats& s = framer.stats();
  Check(s.bytes_in == size);
  Check(s.bytes_in == s.bytes_in_frames + s.skipped_bytes);

  static xs::XsensStreamDecoder decoder;
  decoder = xs::XsensStreamDecoder{};
  const size_t cut = size > 1 ? data[1] % size : 0;
  decoder.Process({data, cut}, 1, 1);
  decoder.Process({data + cut, size - cut}, 2, 2);
  decoder.Restart();
  const xs::XsensStreamStats& d = decoder.stats();
  Check(d.restarts == 1);
  Check(d.framer.bytes_in == size);
  Check(d.framer.bytes_in == d.framer.bytes_in_frames + d.framer.skipped_bytes);
  Check(d.samples + d.error_messages + d.other_messages == d.framer.frames);
  return 0;
}
