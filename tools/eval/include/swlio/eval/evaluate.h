#pragma once
/// @file
/// The evaluation pipelines behind `swlio-eval ape|rpe|kitti`, in evo's order: read both
/// files, associate by time (TUM) or by index (KITTI), align the estimate, then compute the
/// metric on the aligned pairs.

#include "swlio/eval/alignment.h"
#include "swlio/eval/association.h"
#include "swlio/eval/metrics.h"
#include "swlio/eval/trajectory.h"

#include <filesystem>
#include <string>

namespace swlio::eval {

enum class Format { kTum, kKitti };
Format ParseFormat(const std::string& text);  ///< "tum" or "kitti"

/// Two trajectories with pose i of one paired with pose i of the other.
struct PairedTrajectories {
  Trajectory ref;
  Trajectory est;
};

/// Pairs TUM trajectories by nearest stamp; KITTI trajectories by index (sizes must match).
PairedTrajectories Pair(const Trajectory& ref,
                        const Trajectory& est,
                        Format format,
                        const AssociationOptions& association = {});

/// Reads and pairs two files; `kitti_times` (optional) gives the stamps of both KITTI files.
PairedTrajectories LoadPaired(const std::filesystem::path& ref_path,
                              const std::filesystem::path& est_path,
                              Format format,
                              const std::filesystem::path& kitti_times = {},
                              const AssociationOptions& association = {});

struct ApeOptions {
  Alignment alignment = Alignment::kNone;  ///< evo_ape default: no alignment
  PoseRelation relation = PoseRelation::kTranslation;
};

struct RpeOptions {
  Alignment alignment = Alignment::kNone;
  PoseRelation relation = PoseRelation::kTranslation;
  double delta = 1.0;  ///< evo_rpe default: 1 frame
  DeltaUnit delta_unit = DeltaUnit::kFrames;
};

struct Evaluation {
  PairedTrajectories data;                  ///< the reference and the aligned estimate
  Sim3Transform alignment;                  ///< what was applied to the estimate
  std::vector<double> errors;               ///< one per pose (APE) or per pair (RPE)
  std::vector<std::size_t> error_pose_ids;  ///< pose index each error belongs to (RPE: j)
  Statistics stats;
};

/// Aligns `data.est` and computes the APE.
Evaluation EvaluateApe(PairedTrajectories data, const ApeOptions& options);
/// Aligns `data.est` and computes the RPE (pairs chosen on the aligned estimate).
Evaluation EvaluateRpe(PairedTrajectories data, const RpeOptions& options);

}  // namespace swlio::eval
