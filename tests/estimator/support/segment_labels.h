#pragma once
// The labels a Segmenter with `config` gives the points of `scan` (one per input point).

#include <cstdint>
#include <vector>

#include "swlio/estimator/frontend/segmentation.h"

namespace swlio::estimator::test {

inline std::vector<int32_t> SegmentLabels(const SegmentationConfig& config, const Scan& scan) {
  Segmenter segmenter(config);
  SegmentationResult r;
  segmenter.Segment(scan, &r);
  return r.labels;
}

}  // namespace swlio::estimator::test
