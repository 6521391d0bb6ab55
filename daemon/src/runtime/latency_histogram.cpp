#include "swlio/daemon/runtime/latency_histogram.h"

#include <cmath>

namespace swlio::daemon {
namespace {

constexpr double kFirstEdgeNs = 25'000.0;
constexpr double kBinsPerOctave = 4.0;

double EdgeMs(int bin) { return static_cast<double>(LatencyHistogram::UpperEdgeNs(bin)) * 1e-6; }

}  // namespace

int LatencyHistogram::Bin(int64_t latency_ns) {
  if (latency_ns <= static_cast<int64_t>(kFirstEdgeNs)) return 0;
  const double bin =
      std::ceil(kBinsPerOctave * std::log2(static_cast<double>(latency_ns) / kFirstEdgeNs));
  return bin >= kBins - 1 ? kBins - 1 : static_cast<int>(bin);
}

int64_t LatencyHistogram::UpperEdgeNs(int bin) {
  const int b = bin < kBins - 1 ? bin : kBins - 2;
  return static_cast<int64_t>(kFirstEdgeNs * std::exp2(static_cast<double>(b) / kBinsPerOctave));
}

void LatencyHistogram::Add(int64_t latency_ns) {
  std::atomic<uint64_t>& c = counts_[static_cast<size_t>(Bin(latency_ns))];
  c.store(c.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);  // one writer
}

LatencyHistogram::Counts LatencyHistogram::Snapshot() const {
  Counts out{};
  for (size_t i = 0; i < out.size(); ++i) out[i] = counts_[i].load(std::memory_order_relaxed);
  return out;
}

LatencySummary Summarize(const LatencyHistogram::Counts& now,
                         const LatencyHistogram::Counts& before) {
  LatencyHistogram::Counts d{};
  LatencySummary s;
  for (size_t i = 0; i < d.size(); ++i) {
    d[i] = now[i] >= before[i] ? now[i] - before[i] : 0;
    s.count += d[i];
  }
  if (s.count == 0) return s;
  uint64_t seen = 0;
  const auto rank50 = static_cast<uint64_t>(std::ceil(0.50 * static_cast<double>(s.count)));
  const auto rank99 = static_cast<uint64_t>(std::ceil(0.99 * static_cast<double>(s.count)));
  for (int i = 0; i < LatencyHistogram::kBins; ++i) {
    const uint64_t n = d[static_cast<size_t>(i)];
    if (n == 0) continue;
    if (seen < rank50 && seen + n >= rank50) s.p50_ms = EdgeMs(i);
    if (seen < rank99 && seen + n >= rank99) s.p99_ms = EdgeMs(i);
    seen += n;
    s.max_ms = EdgeMs(i);
  }
  return s;
}

}  // namespace swlio::daemon
