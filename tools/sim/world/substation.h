#pragma once
/// @file
/// Procedural outdoor substation, fully determined by a seed.
///
/// Fixed layout (metres, world frame x east, y north, z up), details drawn from the seed:
/// - perimeter fence x ∈ [−12, 205], y ∈ [−8, 135];
/// - a ring road (centre lines x = 45 and 195, y = 12 and 118) with a middle road at y = 65;
///   roads are kept clear ±4 m around their centre lines;
/// - equipment bays between the roads (two rows of five): transformers with fire walls, or
///   switchgear rows of insulator stacks; a gantry with beams and busbars over every bay;
/// - lighting poles along the roads, cable-trench covers beside the middle road, bumps across
///   the roads, trees along the north fence, a control building in the north-west;
/// - an open yard x ∈ [−12, 40], y ∈ [−8, 105]: gravel and the fence only (poor geometry).

#include <cstdint>

#include "world/world.h"

namespace swlio::sim {

/// Road centre-line coordinates shared by the generator and the scenarios.
struct Layout {
  static constexpr double kFenceMinX = -12.0, kFenceMaxX = 205.0;
  static constexpr double kFenceMinY = -8.0, kFenceMaxY = 135.0;
  static constexpr double kRoadWest = 45.0, kRoadEast = 195.0;
  static constexpr double kRoadSouth = 12.0, kRoadMiddle = 65.0, kRoadNorth = 118.0;
  static constexpr double kYardMaxX = 40.0;
  static constexpr double kRoadClearance = 4.0;
};

/// Builds the world for `seed` (acceleration grid included).
World GenerateSubstation(uint64_t seed);

}  // namespace swlio::sim
