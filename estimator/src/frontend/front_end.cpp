#include "swlio/estimator/frontend/front_end.h"

namespace swlio::estimator {

ConfigIssues FrontEndConfig::Validate() const {
  ConfigIssues issues;
  AppendWithPrefix(issues, "segmentation", segmentation.Validate());
  AppendWithPrefix(issues, "features", features.Validate());
  AppendWithPrefix(issues, "adaptive", adaptive.Validate());
  CheckThat(issues, plane_voxel_m == 0.0 || (plane_voxel_m >= 0.01 && plane_voxel_m <= 10.0),
            "plane_voxel_m", "must be 0 (adaptive) or in [0.01, 10] m");
  CheckThat(issues, edge_voxel_m == 0.0 || (edge_voxel_m >= 0.01 && edge_voxel_m <= 10.0),
            "edge_voxel_m", "must be 0 (adaptive) or in [0.01, 10] m");
  return issues;
}

FrontEnd::FrontEnd(const FrontEndConfig& config)
    : config_(config), segmenter_(config.segmentation), extractor_(config.features) {}

void FrontEnd::Process(const Scan& scan, FrontEndOutput* out) {
  segmenter_.Segment(scan, &out->segmentation);
  extractor_.Extract(out->segmentation, &out->features);
  out->plane_filter = config_.plane_voxel_m > 0.0
                          ? filter_.Apply(&out->features.planes, config_.plane_voxel_m)
                          : filter_.Apply(&out->features.planes, config_.adaptive);
  out->edge_filter = config_.edge_voxel_m > 0.0
                         ? filter_.Apply(&out->features.edges, config_.edge_voxel_m)
                         : filter_.Apply(&out->features.edges, config_.adaptive);
}

}  // namespace swlio::estimator
