#pragma once
/// @file
/// One-line JSON for evaluation results (what `swlio-eval --json` prints). Doubles are written
/// with "%.17g", so they read back to the identical value.

#include "swlio/eval/kitti_metric.h"
#include "swlio/eval/metrics.h"

#include <string>

namespace swlio::eval {

/// "%.17g" of `value` (non-finite values as JSON null).
std::string FormatExact(double value);

/// {"n": …, "max": …, "mean": …, "median": …, "min": …, "rmse": …, "sse": …, "std": …}
std::string ToJson(const Statistics& stats);

/// {"n_segments": …, "t_err_percent": …, "r_err_deg_per_100m": …, "per_length": [{…}, …]}
std::string ToJson(const KittiResult& result);

}  // namespace swlio::eval
