// Xbus stream → MTData2 samples with PacketCounter accounting (see xsens_stream_decoder.h).
// Protocol facts live in xbus.h and mtdata2.h (Xsens MT0101P).

#include "swlio/drivers/xsens/xsens_stream_decoder.h"

namespace swlio::drivers::xsens {

void Accumulate(const XbusFramerStats& b, XbusFramerStats* a) {
  a->bytes_in += b.bytes_in;
  a->frames += b.frames;
  a->bytes_in_frames += b.bytes_in_frames;
  a->checksum_errors += b.checksum_errors;
  a->skipped_bytes += b.skipped_bytes;
  a->oversize += b.oversize;
  a->bad_bid += b.bad_bid;
}

const XsensStreamStats& XsensStreamDecoder::stats() const {
  stats_view_ = stats_;
  Accumulate(framer_.stats(), &stats_view_.framer);
  return stats_view_;
}

void XsensStreamDecoder::Restart() {
  framer_.Flush();
  Accumulate(framer_.stats(), &stats_.framer);
  framer_ = XbusFramer{};
  last_counter_.reset();
}

void XsensStreamDecoder::Process(std::span<const uint8_t> bytes,
                                 int64_t t_host_ns,
                                 uint32_t epoch) {
  if (epoch_ != epoch) {
    if (epoch_) ++stats_.restarts;
    Restart();
    epoch_ = epoch;
  }
  XbusFrame frame;
  while (!bytes.empty()) {
    bytes = bytes.subspan(framer_.Feed(bytes));
    while (framer_.Next(&frame)) OnFrame(frame, t_host_ns);
  }
}

void XsensStreamDecoder::OnFrame(const XbusFrame& frame, int64_t t_host_ns) {
  if (frame.mid != mid::kMtData2) {
    ++(frame.mid == mid::kError ? stats_.error_messages : stats_.other_messages);
    return;
  }
  if (DecodeMtData2(frame.payload, &sample_) != MtData2Status::kOk) ++stats_.truncated;
  ++stats_.samples;
  stats_.unknown_items += sample_.unknown_items;
  stats_.bad_size_items += sample_.bad_size_items;
  if (sample_.packet_counter) {
    const uint16_t c = *sample_.packet_counter;
    if (last_counter_) {
      const auto step = static_cast<uint16_t>(c - *last_counter_);
      if (step != 1) ++stats_.counter_gaps;
      // Forward jumps count as losses; repeats and backward jumps (device reset) do not.
      if (step > 1 && step < 0x8000) stats_.missing_packets += step - 1u;
    }
    last_counter_ = c;
  }
  last_frame_bytes_ = frame.frame_bytes;
  if (sink_) sink_(sample_, t_host_ns);
}

}  // namespace swlio::drivers::xsens
