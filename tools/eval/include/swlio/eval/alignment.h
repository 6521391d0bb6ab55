#pragma once
/// @file
/// Alignment of an estimated trajectory to a reference, with evo's conventions.
///
/// Umeyama (S. Umeyama, "Least-squares estimation of transformation parameters between two
/// point patterns", IEEE PAMI 13(4), 1991, eqs. 34–43): finds s, R, t minimising
/// Σ‖y_i − (s R x_i + t)‖² over paired points x (source) and y (target):
///   μx, μy means; σx² = (1/n) Σ‖x_i − μx‖²; Σxy = (1/n) Σ (y_i − μy)(x_i − μx)ᵀ = U D Vᵀ;
///   S = diag(1, 1, −1) if det(U) det(V) < 0 else I; R = U S Vᵀ; s = tr(D S)/σx²; t = μy − s R μx.
/// Applying it to a trajectory (evo's `PosePath3D.align`): positions are scaled by s (rotations
/// untouched), then every pose is left-multiplied by [R t; 0 1].
/// Origin alignment (evo's `align_origin`): every pose is left-multiplied by
/// T_ref[0] · T_est[0]⁻¹, so the first poses coincide.

#include "swlio/eval/trajectory.h"

#include <Eigen/Core>

#include <string>

namespace swlio::eval {

enum class Alignment { kNone, kSe3, kSim3, kOrigin };

/// Parses "none", "se3", "sim3", "origin"; throws EvalError otherwise.
Alignment ParseAlignment(const std::string& text);
std::string ToString(Alignment alignment);

/// y ≈ scale · R · x + t.
struct Sim3Transform {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  double scale = 1.0;
};

/// Umeyama's least-squares fit from `source` to `target` (3×n each, n ≥ 2); with_scale = false
/// fixes s = 1. Throws EvalError on mismatched sizes or a covariance of rank < 2 (e.g. all
/// points equal or fewer than 2 points), as evo does.
Sim3Transform Umeyama(const Eigen::Matrix3Xd& source,
                      const Eigen::Matrix3Xd& target,
                      bool with_scale);

/// Inverse of a pose whose rotation block is inverted by transposition (evo's se3_inverse).
Pose InverseRigid(const Pose& T);

/// Aligns `est` to `ref` in place (paired pose by pose, same size); returns the transform that
/// was applied (identity for kNone; scale 1 except for kSim3).
Sim3Transform Align(Trajectory& est, const Trajectory& ref, Alignment alignment);

}  // namespace swlio::eval
