#include "latency_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "swlio/core/time.h"

namespace swlio::tools::echo {
namespace {

/// The q-quantile (nearest rank) of `v`, which it sorts.
int64_t Quantile(std::vector<int64_t>& v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(std::lround(q * static_cast<double>(v.size() - 1)))];
}

}  // namespace

LatencySummary::LatencySummary(std::ostream* out, double period_s)
    : out_(out), period_ns_(std::max<int64_t>(SecToNs(period_s), kNsPerMs)) {
  *out_ << kLatencySummaryHeader << "\n";
}

void LatencySummary::Add(ipc::Topic topic,
                         int64_t receive_steady_ns,
                         int64_t transport_ns,
                         int64_t age_ns) {
  if (first_ns_ < 0) {
    first_ns_ = receive_steady_ns;
    interval_end_ns_ = first_ns_ + period_ns_;
  }
  while (receive_steady_ns >= interval_end_ns_) {  // intervals without samples write nothing
    WriteRows(interval_end_ns_);
    interval_end_ns_ += period_ns_;
  }
  last_ns_ = std::max(last_ns_, receive_steady_ns);
  Samples& s = samples_[static_cast<size_t>(topic)];
  s.transport_ns.push_back(transport_ns);
  s.age_ns.push_back(age_ns);
}

void LatencySummary::Flush() {
  if (first_ns_ >= 0) WriteRows(last_ns_);
  out_->flush();
}

void LatencySummary::WriteRows(int64_t end_ns) {
  for (size_t i = 0; i < samples_.size(); ++i) {
    Samples& s = samples_[i];
    if (s.age_ns.empty()) continue;
    char row[256];
    std::snprintf(row, sizeof row, "%.3f,%s,%zu,%.1f,%.1f,%.1f,%.3f,%.3f,%.3f",
                  NsToSec(end_ns - first_ns_), ipc::TopicLabel(static_cast<ipc::Topic>(i)),
                  s.age_ns.size(), static_cast<double>(Quantile(s.transport_ns, 0.5)) * 1e-3,
                  static_cast<double>(Quantile(s.transport_ns, 0.99)) * 1e-3,
                  static_cast<double>(s.transport_ns.back()) * 1e-3,
                  static_cast<double>(Quantile(s.age_ns, 0.5)) * 1e-6,
                  static_cast<double>(Quantile(s.age_ns, 0.99)) * 1e-6,
                  static_cast<double>(s.age_ns.back()) * 1e-6);
    *out_ << row << "\n";
    s.transport_ns.clear();
    s.age_ns.clear();
  }
}

}  // namespace swlio::tools::echo
