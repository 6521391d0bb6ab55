// Nearest-stamp association of two trajectories; the conventions are evo's (see association.h).

#include "swlio/eval/association.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace swlio::eval {
namespace {

/// Index of the first minimum of |target[k] + offset − t| by a full scan (any order).
std::size_t NearestByScan(const std::vector<double>& target_s, double offset_s, double t) {
  std::size_t best = 0;
  double best_diff = std::abs(target_s[0] + offset_s - t);
  for (std::size_t k = 1; k < target_s.size(); ++k) {
    const double diff = std::abs(target_s[k] + offset_s - t);
    if (diff < best_diff) {
      best_diff = diff;
      best = k;
    }
  }
  return best;
}

/// Same result as NearestByScan for non-decreasing `shifted_s`, in O(log n).
std::size_t NearestSorted(const std::vector<double>& shifted_s, double t) {
  const auto it = std::lower_bound(shifted_s.begin(), shifted_s.end(), t);
  const auto k = static_cast<std::size_t>(it - shifted_s.begin());
  std::size_t best = k < shifted_s.size() ? k : shifted_s.size() - 1;
  if (k > 0 &&
      (k == shifted_s.size() || std::abs(shifted_s[k - 1] - t) <= std::abs(shifted_s[k] - t))) {
    best = k - 1;
  }
  // First occurrence of an equal stamp, as a scan would find it.
  const auto first = std::lower_bound(shifted_s.begin(), shifted_s.end(), shifted_s[best]);
  return static_cast<std::size_t>(first - shifted_s.begin());
}

}  // namespace

Association NearestStamps(const std::vector<double>& query_s,
                          const std::vector<double>& target_s,
                          double max_diff_s,
                          double offset_s) {
  Association out;  // ref_ids hold query indices, est_ids target indices
  if (target_s.empty()) return out;
  std::vector<double> shifted_s(target_s.size());
  std::transform(target_s.begin(), target_s.end(), shifted_s.begin(),
                 [offset_s](double t) { return t + offset_s; });
  const bool sorted = std::is_sorted(shifted_s.begin(), shifted_s.end());
  for (std::size_t q = 0; q < query_s.size(); ++q) {
    const std::size_t k = sorted ? NearestSorted(shifted_s, query_s[q])
                                 : NearestByScan(target_s, offset_s, query_s[q]);
    if (std::abs(shifted_s[k] - query_s[q]) <= max_diff_s) {
      out.ref_ids.push_back(q);
      out.est_ids.push_back(k);
    }
  }
  return out;
}

Association AssociateByTime(const std::vector<double>& ref_stamps_s,
                            const std::vector<double>& est_stamps_s,
                            const AssociationOptions& options) {
  const bool est_longer = est_stamps_s.size() > ref_stamps_s.size();
  Association out;
  if (est_longer) {
    // Query the reference (short) against the estimate shifted by the offset.
    out = NearestStamps(ref_stamps_s, est_stamps_s, options.max_diff_s, options.est_offset_s);
  } else {
    const Association m =
        NearestStamps(est_stamps_s, ref_stamps_s, options.max_diff_s, -options.est_offset_s);
    out.ref_ids = m.est_ids;
    out.est_ids = m.ref_ids;
  }
  if (out.ref_ids.empty()) {
    std::ostringstream os;
    os << "no matching timestamps between reference and estimate with max. time diff "
       << options.max_diff_s << " s and offset " << options.est_offset_s << " s";
    throw EvalError(os.str());
  }
  return out;
}

}  // namespace swlio::eval
