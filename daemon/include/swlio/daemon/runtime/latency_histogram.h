#pragma once
/// @file
/// A latency distribution that one thread writes and any thread reads, without locks: counts in
/// log-spaced bins (four per octave, 25 µs to about 5 s, the last bin open-ended). Health turns
/// two snapshots into the quantiles of the interval between them.

#include <array>
#include <atomic>
#include <cstdint>

namespace swlio::daemon {

class LatencyHistogram {
 public:
  static constexpr int kBins = 72;
  using Counts = std::array<uint64_t, kBins>;

  /// Adds one latency (negative values count as 0). Only one thread may call it.
  void Add(int64_t latency_ns);
  Counts Snapshot() const;

  static int Bin(int64_t latency_ns);
  /// The upper edge of `bin` (ns): 25 µs · 2^(bin/4); the last bin has none (its lower edge).
  static int64_t UpperEdgeNs(int bin);

 private:
  std::array<std::atomic<uint64_t>, kBins> counts_{};
};

/// Quantiles of what was added between two snapshots (`before` may be all zeros).
struct LatencySummary {
  uint64_t count = 0;
  double p50_ms = 0.0;  ///< bin upper edges: an upper bound within 19 %
  double p99_ms = 0.0;
  double max_ms = 0.0;
};
LatencySummary Summarize(const LatencyHistogram::Counts& now,
                         const LatencyHistogram::Counts& before);

}  // namespace swlio::daemon
