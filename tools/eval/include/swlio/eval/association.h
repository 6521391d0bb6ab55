#pragma once
/// @file
/// Association of two time-stamped trajectories by nearest stamp, as evo's
/// `sync.associate_trajectories` (nearest_time method) does it:
/// - the trajectory with fewer poses ("short") is matched against the other ("long"); on a tie
///   the second (estimate) is the short one;
/// - each short stamp takes the long stamp with the smallest |t_long + offset − t_short| (the
///   first such index on ties) and keeps the pair when that difference is ≤ max_diff_s;
/// - a long pose may be matched more than once, and the pairs follow the short trajectory's order.

#include "swlio/eval/trajectory.h"

#include <cstddef>
#include <vector>

namespace swlio::eval {

struct AssociationOptions {
  double max_diff_s = 0.01;   ///< evo's default `--t_max_diff`
  double est_offset_s = 0.0;  ///< added to the estimate's stamps (evo's `--t_offset`)
};

struct Association {
  std::vector<std::size_t> ref_ids;  ///< index into the reference, one per pair
  std::vector<std::size_t> est_ids;  ///< index into the estimate, one per pair
};

/// Nearest-stamp matching; throws EvalError when no pair is found.
Association AssociateByTime(const std::vector<double>& ref_stamps_s,
                            const std::vector<double>& est_stamps_s,
                            const AssociationOptions& options = {});

/// For each of `query_s`, the index of the nearest of `target_s + offset_s` (first on ties) and
/// keeps it when within `max_diff_s`; returns (query index, target index) lists.
Association NearestStamps(const std::vector<double>& query_s,
                          const std::vector<double>& target_s,
                          double max_diff_s,
                          double offset_s);

}  // namespace swlio::eval
