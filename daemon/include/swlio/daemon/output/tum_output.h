#pragma once
/// @file
/// One estimated state as a TUM trajectory line (stamp in s with ns digits, position, unit
/// quaternion with w ≥ 0), the format swlio-run and swlio-replay write: one function, so their
/// outputs stay byte-identical.

#include <ostream>

#include "swlio/core/types.h"

namespace swlio::daemon {

void WriteTumLine(std::ostream& out, const State& state);

}  // namespace swlio::daemon
