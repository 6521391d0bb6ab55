// libFuzzer target for the daemon's configuration loader (issue 9: "the config loader fuzzed
// too"): the input is the text of a configuration file. Whatever it holds, LoadConfigText
// must return (no exception escapes, no sanitizer report, no hang) and its answer must be
// consistent. Any violated invariant is a bug (__builtin_trap).
//
// Invariants:
// - an accepted configuration passes its own Validate() (nothing invalid slips through);
// - an accepted configuration, printed (swliod --print-config), loads again without an error
//   and prints the same (--print-config | --check-config - holds for every accepted file);
// - every error names a reason, and a line only together with a column (file:line:column);
// - loading is a function of the text: the same text twice gives the same errors.
//
// Seeds: config/swlio.yaml and the example configurations (scripts/fuzz copies them).

#include <cstddef>
#include <cstdint>
#include <string>

#include "swlio/daemon/config/config_loader.h"
#include "swlio/daemon/config/config_printer.h"

namespace {

void Check(bool ok) {
  if (!ok) __builtin_trap();
}

bool SameErrors(const swlio::daemon::LoadedConfig& a, const swlio::daemon::LoadedConfig& b) {
  if (a.errors.size() != b.errors.size()) return false;
  for (size_t i = 0; i < a.errors.size(); ++i) {
    if (a.errors[i].ToString() != b.errors[i].ToString()) return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto loaded = swlio::daemon::LoadConfigText(text, "fuzz.yaml", "/etc/swlio");
  if (loaded.ok()) {
    Check(loaded.config.Validate().empty());
    const std::string printed = swlio::daemon::PrintConfig(loaded.config);
    const auto again = swlio::daemon::LoadConfigText(printed, "printed.yaml", "/elsewhere");
    Check(again.ok());
    Check(swlio::daemon::PrintConfig(again.config) == printed);
  }
  for (const auto& e : loaded.errors) {
    Check(!e.reason.empty());
    Check(e.file == "fuzz.yaml");
    Check(e.line >= 0 && e.column >= 0 && (e.line == 0) == (e.column == 0));
  }
  Check(SameErrors(loaded, swlio::daemon::LoadConfigText(text, "fuzz.yaml", "/etc/swlio")));
  return 0;
}
