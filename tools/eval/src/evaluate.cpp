// APE/RPE pipelines: pair, align, compute, summarise (see evaluate.h).

#include "swlio/eval/evaluate.h"

#include <numeric>

namespace swlio::eval {

Format ParseFormat(const std::string& text) {
  if (text == "tum") return Format::kTum;
  if (text == "kitti") return Format::kKitti;
  throw EvalError("unknown trajectory format '" + text + "' (expected tum or kitti)");
}

PairedTrajectories Pair(const Trajectory& ref,
                        const Trajectory& est,
                        Format format,
                        const AssociationOptions& association) {
  if (format == Format::kKitti) {
    if (ref.Size() != est.Size()) {
      throw EvalError("KITTI trajectories must have the same number of poses (reference " +
                      std::to_string(ref.Size()) + ", estimate " + std::to_string(est.Size()) +
                      ")");
    }
    return {ref, est};
  }
  if (!ref.HasStamps() || !est.HasStamps()) {
    throw EvalError("time association needs stamps on both trajectories");
  }
  const Association a = AssociateByTime(ref.stamps_s, est.stamps_s, association);
  return {ref.Select(a.ref_ids), est.Select(a.est_ids)};
}

PairedTrajectories LoadPaired(const std::filesystem::path& ref_path,
                              const std::filesystem::path& est_path,
                              Format format,
                              const std::filesystem::path& kitti_times,
                              const AssociationOptions& association) {
  if (format == Format::kTum) {
    if (!kitti_times.empty()) throw EvalError("a timestamp file only applies to KITTI files");
    return Pair(ReadTumFile(ref_path), ReadTumFile(est_path), format, association);
  }
  return Pair(ReadKittiFile(ref_path, kitti_times), ReadKittiFile(est_path, kitti_times), format,
              association);
}

Evaluation EvaluateApe(PairedTrajectories data, const ApeOptions& options) {
  Evaluation out;
  out.alignment = Align(data.est, data.ref, options.alignment);
  out.errors = ApeErrors(data.ref, data.est, options.relation);
  out.error_pose_ids.resize(out.errors.size());
  std::iota(out.error_pose_ids.begin(), out.error_pose_ids.end(), std::size_t{0});
  out.stats = ComputeStatistics(out.errors);
  out.data = std::move(data);
  return out;
}

Evaluation EvaluateRpe(PairedTrajectories data, const RpeOptions& options) {
  Evaluation out;
  out.alignment = Align(data.est, data.ref, options.alignment);
  RpeResult rpe = Rpe(data.ref, data.est, options.delta, options.delta_unit, options.relation);
  out.errors = std::move(rpe.errors);
  for (const auto& pair : rpe.pairs) out.error_pose_ids.push_back(pair.second);
  out.stats = ComputeStatistics(out.errors);
  out.data = std::move(data);
  return out;
}

}  // namespace swlio::eval
