#include "scenarios/trajectory.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "swlio/core/lie.h"

namespace swlio::sim {
namespace {

constexpr double kStep = 0.02;  ///< path table spacing, m
constexpr double kPi = std::numbers::pi;

double WrapPi(double a) {
  while (a > kPi) a -= 2.0 * kPi;
  while (a < -kPi) a += 2.0 * kPi;
  return a;
}

/// Heading change after arc length s of a sin² curvature turn of total angle theta, length len.
double TurnHeading(double s, double len, double theta) {
  const double u = std::clamp(s / len, 0.0, 1.0);
  return theta * (u - std::sin(2.0 * kPi * u) / (2.0 * kPi));
}

/// Distance from the corner at which a turn of this shape must start (symmetric: also where it
/// ends after the corner), from the end point of the turn integrated in its own frame.
double TurnSetback(double len, double theta) {
  const int n = 2000;
  const double h = len / n;
  double x = 0.0, y = 0.0;
  for (int i = 0; i < n; ++i) {  // Simpson on each step
    const double s = i * h;
    const double p0 = TurnHeading(s, len, theta), pm = TurnHeading(s + 0.5 * h, len, theta);
    const double p1 = TurnHeading(s + h, len, theta);
    x += h / 6.0 * (std::cos(p0) + 4.0 * std::cos(pm) + std::cos(p1));
    y += h / 6.0 * (std::sin(p0) + 4.0 * std::sin(pm) + std::sin(p1));
  }
  const double b = y / std::sin(theta);
  return x - b * std::cos(theta);  // = b for a symmetric profile
}

/// Distance covered by a smoothstep speed change va → vb at mean acceleration acc.
double ChangeDistance(double va, double vb, double acc) {
  return 0.5 * (va + vb) * std::abs(vb - va) / acc;
}

}  // namespace

Trajectory::Trajectory(const RouteSpec& spec, const Terrain* terrain)
    : terrain_(terrain), imu_height_m_(spec.imu_height_m) {
  if (spec.waypoints.size() < 2) throw std::invalid_argument("a route needs two waypoints");
  BuildPath(spec);
  BuildSpeedProfile(spec);
}

void Trajectory::BuildPath(const RouteSpec& spec) {
  const auto& w = spec.waypoints;
  const size_t n = w.size();
  std::vector<double> leg_heading(n - 1), setback(n, 0.0), turn_len(n, 0.0), turn(n, 0.0);
  for (size_t i = 0; i + 1 < n; ++i) {
    const Eigen::Vector2d d = w[i + 1].xy - w[i].xy;
    leg_heading[i] = std::atan2(d.y(), d.x());
  }
  for (size_t i = 1; i + 1 < n; ++i) {
    turn[i] = WrapPi(leg_heading[i] - leg_heading[i - 1]);
    if (std::abs(turn[i]) < 1e-6) continue;
    if (std::abs(turn[i]) > 170.0 * kPi / 180.0) {
      throw std::invalid_argument("route turn sharper than 170° at waypoint " + std::to_string(i));
    }
    turn_len[i] = 2.0 * std::abs(turn[i]) * w[i].turn_radius_m;
    setback[i] = TurnSetback(turn_len[i], turn[i]);
  }
  double s = 0.0;
  for (size_t i = 0; i + 1 < n; ++i) {
    const double straight = (w[i + 1].xy - w[i].xy).norm() - setback[i] - setback[i + 1];
    if (straight < 0.0) {
      throw std::invalid_argument("route leg " + std::to_string(i) + " too short for its turns");
    }
    segments_.push_back({s, straight, 0.0, leg_heading[i]});
    s += straight;
    if (i + 2 < n && turn_len[i + 1] > 0.0) {
      segments_.push_back({s, turn_len[i + 1], turn[i + 1], leg_heading[i]});
      s += turn_len[i + 1];
    }
  }
  length_m_ = s;
  // Position table by Simpson integration of the (analytic) heading.
  const size_t knots = static_cast<size_t>(std::ceil(length_m_ / kStep)) + 1;
  table_xy_.resize(knots);
  table_xy_[0] = w[0].xy;
  for (size_t k = 1; k < knots; ++k) {
    const double s0 = static_cast<double>(k - 1) * kStep;
    const double p0 = Heading(s0), pm = Heading(s0 + 0.5 * kStep), p1 = Heading(s0 + kStep);
    table_xy_[k] =
        table_xy_[k - 1] + kStep / 6.0 *
                               Eigen::Vector2d(std::cos(p0) + 4.0 * std::cos(pm) + std::cos(p1),
                                               std::sin(p0) + 4.0 * std::sin(pm) + std::sin(p1));
  }
}

void Trajectory::AddPhase(double duration, double v0, double v1) {
  if (duration <= 0.0) return;
  Phase p{duration_s_, duration, v0, v1, 0.0};
  p.s0 = phases_.empty() ? 0.0
                         : phases_.back().s0 + 0.5 * (phases_.back().v0 + phases_.back().v1) *
                                                   phases_.back().duration;
  phases_.push_back(p);
  duration_s_ += duration;
}

void Trajectory::BuildSpeedProfile(const RouteSpec& spec) {
  auto turn_speed = [&](const Segment& seg) {
    const double radius = seg.length / (2.0 * std::abs(seg.theta));
    return std::min({spec.cruise_speed_mps, spec.max_yaw_rate_radps * radius,
                     std::sqrt(spec.max_lateral_acc_mps2 * radius)});
  };
  const double acc = spec.mean_acc_mps2;
  AddPhase(spec.stand_start_s, 0.0, 0.0);
  for (size_t j = 0; j < segments_.size(); ++j) {
    const Segment& seg = segments_[j];
    if (seg.theta != 0.0) {
      const double v = turn_speed(seg);
      AddPhase(seg.length / v, v, v);
      continue;
    }
    const double v_in = j > 0 ? turn_speed(segments_[j - 1]) : 0.0;
    const double v_out = j + 1 < segments_.size() ? turn_speed(segments_[j + 1]) : 0.0;
    double v_top = spec.cruise_speed_mps;
    const double v_floor = std::max(v_in, v_out);
    while (v_top > v_floor &&
           ChangeDistance(v_in, v_top, acc) + ChangeDistance(v_top, v_out, acc) > seg.length) {
      v_top = std::max(v_floor, v_top - 0.01);
    }
    const double d_up = ChangeDistance(v_in, v_top, acc);
    const double d_down = ChangeDistance(v_top, v_out, acc);
    if (d_up + d_down > seg.length + 1e-9) {
      throw std::invalid_argument("route straight too short for its speed changes");
    }
    AddPhase(std::abs(v_top - v_in) / acc, v_in, v_top);
    if (v_top > 0.0) AddPhase((seg.length - d_up - d_down) / v_top, v_top, v_top);
    AddPhase(std::abs(v_top - v_out) / acc, v_top, v_out);
  }
  AddPhase(spec.stand_end_s, 0.0, 0.0);
}

double Trajectory::Heading(double s) const {
  s = std::clamp(s, 0.0, length_m_);
  auto it = std::upper_bound(segments_.begin(), segments_.end(), s,
                             [](double v, const Segment& seg) { return v < seg.s0; });
  const Segment& seg = *std::prev(it == segments_.begin() ? std::next(it) : it);
  if (seg.theta == 0.0) return seg.psi0;
  return seg.psi0 + TurnHeading(s - seg.s0, seg.length, seg.theta);
}

double Trajectory::Curvature(double s) const {
  s = std::clamp(s, 0.0, length_m_);
  auto it = std::upper_bound(segments_.begin(), segments_.end(), s,
                             [](double v, const Segment& seg) { return v < seg.s0; });
  const Segment& seg = *std::prev(it == segments_.begin() ? std::next(it) : it);
  if (seg.theta == 0.0) return 0.0;
  const double u = std::clamp((s - seg.s0) / seg.length, 0.0, 1.0);
  const double sn = std::sin(kPi * u);
  return 2.0 * seg.theta / seg.length * sn * sn;
}

Eigen::Vector2d Trajectory::Position(double s) const {
  s = std::clamp(s, 0.0, length_m_);
  const size_t k = std::min(static_cast<size_t>(s / kStep), table_xy_.size() - 2);
  const double s0 = static_cast<double>(k) * kStep;
  const double u = (s - s0) / kStep;
  const double h0 = Heading(s0), h1 = Heading(s0 + kStep);
  const Eigen::Vector2d m0 = kStep * Eigen::Vector2d(std::cos(h0), std::sin(h0));
  const Eigen::Vector2d m1 = kStep * Eigen::Vector2d(std::cos(h1), std::sin(h1));
  const double u2 = u * u, u3 = u2 * u;  // cubic Hermite
  return (2 * u3 - 3 * u2 + 1) * table_xy_[k] + (u3 - 2 * u2 + u) * m0 +
         (-2 * u3 + 3 * u2) * table_xy_[k + 1] + (u3 - u2) * m1;
}

void Trajectory::SpeedAt(double t, double* s, double* v, double* a) const {
  auto it = std::upper_bound(phases_.begin(), phases_.end(), t,
                             [](double x, const Phase& p) { return x < p.t0; });
  const Phase& p = *std::prev(it == phases_.begin() ? std::next(it) : it);
  const double u = std::clamp((t - p.t0) / p.duration, 0.0, 1.0);
  const double dv = p.v1 - p.v0;
  *v = p.v0 + dv * (3 * u * u - 2 * u * u * u);
  *s = std::min(length_m_, p.s0 + p.duration * (p.v0 * u + dv * (u * u * u - 0.5 * u * u * u * u)));
  *a = (t < p.t0 || t > p.t0 + p.duration) ? 0.0 : dv / p.duration * 6.0 * u * (1.0 - u);
}

Eigen::Matrix3d Trajectory::Attitude(const Eigen::Vector2d& xy, double psi) const {
  const Eigen::Vector2d g = terrain_->Gradient(xy);
  const Eigen::Vector3d n = Eigen::Vector3d(-g.x(), -g.y(), 1.0).normalized();
  const Eigen::Vector3d h(std::cos(psi), std::sin(psi), 0.0);
  const Eigen::Vector3d x = (h - h.dot(n) * n).normalized();
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = n.cross(x);
  R.col(2) = n;
  return R;
}

double Trajectory::DrivenLengthM() const {
  const auto arc_length_at = [this](double t_s) {
    double s = 0.0, v = 0.0, a = 0.0;
    SpeedAt(t_s, &s, &v, &a);
    return s;
  };
  if (lap_period_s_ <= 0.0) return arc_length_at(duration_s_);
  const double laps = std::floor(duration_s_ / lap_period_s_);
  return laps * length_m_ + arc_length_at(duration_s_ - laps * lap_period_s_);
}

void Trajectory::Repeat(int laps, double period_s) {
  lap_period_s_ = std::max(period_s, duration_s_);
  duration_s_ = lap_period_s_ * std::max(laps, 1);
}

bool Trajectory::EndsWhereItStarts() const {
  const Kinematics a = AtInLap(0.0);
  const Kinematics b = AtInLap(lap_period_s_ > 0.0 ? lap_period_s_ : duration_s_);
  const double angle_rad = lie::Log(a.R_world_body.transpose() * b.R_world_body).norm();
  return (a.p_world - b.p_world).norm() < 0.05 && angle_rad < 0.5 * kPi / 180.0 &&
         b.v_world.norm() < 1e-6;
}

Kinematics Trajectory::At(double t) const {
  Kinematics k;
  if (lap_period_s_ <= 0.0) {
    k = AtInLap(t);
  } else {
    const double lap = std::floor(t / lap_period_s_);
    k = AtInLap(lap <= 0.0 ? t : t - lap * lap_period_s_);
  }
  if (vibration_) vibration_->Apply(t, &k);
  return k;
}

Kinematics Trajectory::AtInLap(double t) const {
  double s = 0.0, v = 0.0, a_t = 0.0;
  SpeedAt(t, &s, &v, &a_t);
  const Eigen::Vector2d xy = Position(s);
  const double psi = Heading(s);
  const double kappa = Curvature(s);
  const Eigen::Vector2d tangent(std::cos(psi), std::sin(psi)), normal(-tangent.y(), tangent.x());
  const Eigen::Vector2d v_xy = v * tangent;
  const Eigen::Vector2d a_xy = a_t * tangent + v * v * kappa * normal;
  const Eigen::Vector2d g = terrain_->Gradient(xy);
  Kinematics k;
  k.p_world = Eigen::Vector3d(xy.x(), xy.y(), terrain_->Height(xy) + imu_height_m_);
  k.v_world = Eigen::Vector3d(v_xy.x(), v_xy.y(), g.dot(v_xy));
  k.a_world =
      Eigen::Vector3d(a_xy.x(), a_xy.y(), v_xy.dot(terrain_->Hessian(xy) * v_xy) + g.dot(a_xy));
  k.R_world_body = Attitude(xy, psi);
  // Body rate from the attitude at t ± h (the attitude is smooth; h keeps rounding < 1e-9).
  const double h = 1e-4;
  double s_m = 0.0, s_p = 0.0, dummy_v = 0.0, dummy_a = 0.0;
  SpeedAt(t - h, &s_m, &dummy_v, &dummy_a);
  SpeedAt(t + h, &s_p, &dummy_v, &dummy_a);
  const Eigen::Matrix3d R_m = Attitude(Position(s_m), Heading(s_m));
  const Eigen::Matrix3d R_p = Attitude(Position(s_p), Heading(s_p));
  k.omega_body = k.R_world_body.transpose() * lie::Log(R_p * R_m.transpose()).eval() / (2.0 * h);
  return k;
}

}  // namespace swlio::sim
