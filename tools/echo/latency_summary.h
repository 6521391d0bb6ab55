#pragma once
/// @file
/// Latency over time for long runs (the soak): instead of a CSV row per sample, one row per
/// topic every `period_s` with the count and the percentiles of the interval. A drift (the
/// daemon falling behind) shows as a rising age; its delivery (write → take) separately.

#include <array>
#include <cstdint>
#include <ostream>
#include <vector>

#include "swlio/ipc/messages.h"

namespace swlio::tools::echo {

/// "t_s,topic,count,transport_p50_us,transport_p99_us,transport_max_us,age_p50_ms,
/// age_p99_ms,age_max_ms": t_s is the interval's end (seconds since the first sample),
/// transport = receive − DDS source time (write → take), age = receive − the message's stamp
/// (end to end when the stamp is on CLOCK_MONOTONIC, as swliod's are).
inline constexpr const char* kLatencySummaryHeader =
    "t_s,topic,count,transport_p50_us,transport_p99_us,transport_max_us,age_p50_ms,age_p99_ms,"
    "age_max_ms";

class LatencySummary {
 public:
  LatencySummary(std::ostream* out, double period_s);

  /// One received sample; writes the rows of the interval that `receive_steady_ns` closes.
  void Add(ipc::Topic topic, int64_t receive_steady_ns, int64_t transport_ns, int64_t age_ns);
  /// Writes the rows of the interval in progress (at the end of the run).
  void Flush();

 private:
  struct Samples {
    std::vector<int64_t> transport_ns;
    std::vector<int64_t> age_ns;
  };
  void WriteRows(int64_t end_ns);

  std::ostream* out_;
  int64_t period_ns_;
  int64_t first_ns_ = -1;
  int64_t interval_end_ns_ = 0;
  int64_t last_ns_ = 0;
  std::array<Samples, ipc::kTopicCount> samples_;
};

}  // namespace swlio::tools::echo
