#pragma once
/// @file
/// actors.csv: every actor (world/actors.h) at 10 Hz of the drive, for evaluation:
///   t_ns,id,kind,moves,x_m,y_m,z_m,yaw_rad,half_x_m,half_y_m,half_z_m
/// t_ns is host time (the base of groundtruth.tum); x, y, z the centre of the box around the
/// actor's body in the world frame, yaw about z, half_* that box's half sizes in the actor's
/// frame (x along its heading); kind person|vehicle; moves 1 when it moves at some time during
/// the drive (SimReturn::moving).

#include <cstdint>
#include <functional>
#include <ostream>

#include "world/actors.h"

namespace swlio::sim {

inline constexpr double kActorsCsvRateHz = 10.0;

/// Writes the header and a row per actor every 0.1 s of [0, duration_s], stamped
/// `host_ns(t_s)`. Returns whether the stream is still good.
bool WriteActorsCsv(const ActorSet& set,
                    double duration_s,
                    const std::function<int64_t(double)>& host_ns,
                    std::ostream& out);

}  // namespace swlio::sim
