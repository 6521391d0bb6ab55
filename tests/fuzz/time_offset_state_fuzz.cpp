// libFuzzer target for the time offset file swliod keeps across restarts
// (daemon/state/time_offset_state.h): the input is the file's text. ParseTimeOffsetState must
// return (no exception escapes, no sanitizer report, no hang), and what it accepts must hold.
// Any violated invariant is a bug (__builtin_trap).
//
// Invariants:
// - an accepted file's values are within the documented limits;
// - an accepted file, written again (FormatTimeOffsetState), is accepted, and writing that
//   gives the same text (the values survive the %.9g of the text);
// - a refused file names a reason.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "swlio/daemon/state/time_offset_state.h"

namespace {

void Check(bool ok) {
  if (!ok) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace swlio::daemon;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string error;
  const auto saved = ParseTimeOffsetState(text, &error);
  if (!saved) {
    Check(!error.empty());
    return 0;
  }
  Check(std::isfinite(saved->offset_s) && std::abs(saved->offset_s) <= kMaxSavedTimeOffsetS);
  Check(saved->sigma_s > 0.0 && saved->sigma_s <= kMaxSavedTimeOffsetS);
  Check(saved->updates >= 1);
  const std::string written = FormatTimeOffsetState(*saved);
  const auto again = ParseTimeOffsetState(written, &error);
  Check(again.has_value());
  Check(FormatTimeOffsetState(*again) == written);
  return 0;
}
