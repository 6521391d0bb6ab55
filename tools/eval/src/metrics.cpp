// APE, RPE and statistics with evo's conventions; the definitions are written in metrics.h.

#include "swlio/eval/metrics.h"

#include "swlio/eval/alignment.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace swlio::eval {

PoseRelation ParsePoseRelation(const std::string& text) {
  if (text == "trans" || text == "trans_part") return PoseRelation::kTranslation;
  if (text == "angle_deg") return PoseRelation::kAngleDeg;
  if (text == "angle_rad") return PoseRelation::kAngleRad;
  if (text == "full") return PoseRelation::kFull;
  if (text == "rot_part") return PoseRelation::kRotationPart;
  throw EvalError("unknown pose relation '" + text +
                  "' (expected trans, angle_deg, angle_rad, full or rot_part)");
}

DeltaUnit ParseDeltaUnit(const std::string& text) {
  if (text == "frames" || text == "f") return DeltaUnit::kFrames;
  if (text == "m") return DeltaUnit::kMeters;
  throw EvalError("unknown delta unit '" + text + "' (expected frames or m)");
}

std::string Describe(PoseRelation relation) {
  switch (relation) {
    case PoseRelation::kTranslation:
      return "translation part (m)";
    case PoseRelation::kAngleDeg:
      return "rotation angle (deg)";
    case PoseRelation::kAngleRad:
      return "rotation angle (rad)";
    case PoseRelation::kFull:
      return "full transformation (unit-less)";
    case PoseRelation::kRotationPart:
      return "rotation part (unit-less)";
  }
  return "?";
}

Statistics ComputeStatistics(std::span<const double> errors) {
  if (errors.empty()) throw EvalError("no errors to summarise");
  Statistics s;
  s.n = errors.size();
  const double n = static_cast<double>(s.n);
  s.max = *std::max_element(errors.begin(), errors.end());
  s.min = *std::min_element(errors.begin(), errors.end());
  s.mean = std::accumulate(errors.begin(), errors.end(), 0.0) / n;
  s.sse = std::accumulate(errors.begin(), errors.end(), 0.0,
                          [](double acc, double e) { return acc + e * e; });
  s.rmse = std::sqrt(s.sse / n);
  const double var =
      std::accumulate(errors.begin(), errors.end(), 0.0,
                      [&s](double acc, double e) { return acc + (e - s.mean) * (e - s.mean); }) /
      n;
  s.std = std::sqrt(var);
  std::vector<double> sorted(errors.begin(), errors.end());
  std::sort(sorted.begin(), sorted.end());
  const std::size_t mid = s.n / 2;
  s.median = (s.n % 2 == 1) ? sorted[mid] : 0.5 * (sorted[mid - 1] + sorted[mid]);
  return s;
}

double RotationAngleRad(const Eigen::Matrix3d& R) {
  // Quaternion from the matrix by the largest of (trace, R00, R11, R22) (Markley's choice, as
  // scipy's Rotation.from_matrix), normalised; then θ = 2 atan2(‖v‖, |w|).
  const double tr = R.trace();
  Eigen::Vector4d q;  // x, y, z, w
  int k = 0;
  R.diagonal().maxCoeff(&k);
  if (tr > R(k, k)) {  // ties go to the diagonal, as argmax over (R00, R11, R22, tr)
    q << R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1), 1.0 + tr;
  } else {
    const int i = k;
    const int j = (i + 1) % 3;
    const int l = (j + 1) % 3;
    q(i) = 1.0 - tr + 2.0 * R(i, i);
    q(j) = R(j, i) + R(i, j);
    q(l) = R(l, i) + R(i, l);
    q(3) = R(l, j) - R(j, l);
  }
  q.normalize();
  return 2.0 * std::atan2(q.head<3>().norm(), std::abs(q(3)));
}

double RelationError(const Pose& E, PoseRelation relation) {
  switch (relation) {
    case PoseRelation::kTranslation:
      return E.block<3, 1>(0, 3).norm();
    case PoseRelation::kAngleRad:
      return RotationAngleRad(E.block<3, 3>(0, 0));
    case PoseRelation::kAngleDeg:
      return RotationAngleRad(E.block<3, 3>(0, 0)) * 180.0 / std::numbers::pi;
    case PoseRelation::kFull:
      return (E - Pose::Identity()).norm();
    case PoseRelation::kRotationPart:
      return (E.block<3, 3>(0, 0) - Eigen::Matrix3d::Identity()).norm();
  }
  return 0.0;
}

std::vector<double> ApeErrors(const Trajectory& ref, const Trajectory& est, PoseRelation relation) {
  if (ref.Size() != est.Size()) throw EvalError("APE needs trajectories with equal pose counts");
  std::vector<double> errors(ref.Size());
  for (std::size_t i = 0; i < ref.Size(); ++i) {
    if (relation == PoseRelation::kTranslation) {
      errors[i] = (est.Position(i) - ref.Position(i)).norm();
    } else {
      errors[i] = RelationError(InverseRigid(est.poses[i]) * ref.poses[i], relation);
    }
  }
  return errors;
}

IdPairs RpePairs(const Trajectory& trajectory, double delta, DeltaUnit unit) {
  IdPairs pairs;
  std::vector<std::size_t> ids;
  if (unit == DeltaUnit::kFrames) {
    if (!(delta >= 1.0) || delta != std::floor(delta)) {
      throw EvalError("delta in frames must be an integer >= 1");
    }
    const auto step = static_cast<std::size_t>(delta);
    for (std::size_t i = 0; i < trajectory.Size(); i += step) ids.push_back(i);
  } else {
    if (!(delta > 0.0)) throw EvalError("delta in metres must be > 0");
    double path_m = 0.0;
    for (std::size_t i = 1; i < trajectory.Size(); ++i) {
      path_m += (trajectory.Position(i) - trajectory.Position(i - 1)).norm();
      if (path_m >= delta) {
        ids.push_back(i);
        path_m = 0.0;
      }
    }
  }
  for (std::size_t k = 1; k < ids.size(); ++k) pairs.emplace_back(ids[k - 1], ids[k]);
  if (pairs.empty()) {
    throw EvalError("delta " + std::to_string(delta) +
                    (unit == DeltaUnit::kFrames ? " frames" : " m") +
                    " gives no pose pair; try a smaller delta");
  }
  return pairs;
}

Pose RpeErrorPose(const Pose& Q_i, const Pose& Q_j, const Pose& P_i, const Pose& P_j) {
  const Pose Q_rel = InverseRigid(Q_i) * Q_j;
  const Pose P_rel = InverseRigid(P_i) * P_j;
  return InverseRigid(Q_rel) * P_rel;
}

RpeResult Rpe(const Trajectory& ref,
              const Trajectory& est,
              double delta,
              DeltaUnit unit,
              PoseRelation relation) {
  if (ref.Size() != est.Size()) throw EvalError("RPE needs trajectories with equal pose counts");
  RpeResult out;
  out.pairs = RpePairs(est, delta, unit);
  out.errors.reserve(out.pairs.size());
  for (const auto& [i, j] : out.pairs) {
    const Pose E = RpeErrorPose(ref.poses[i], ref.poses[j], est.poses[i], est.poses[j]);
    out.errors.push_back(RelationError(E, relation));
  }
  return out;
}

}  // namespace swlio::eval
