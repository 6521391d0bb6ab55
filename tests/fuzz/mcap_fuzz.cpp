// libFuzzer target: the MCAP reader on arbitrary file bytes (bag_fuzz_checks.h invariants).
// Seeds: the kept corpus tests/fuzz/corpus/mcap (written by make_bag_seeds from synthetic
// messages) and, in scripts/fuzz, MCAPs exported by make_bag_seeds from the real .db3 bags.

#include <string>

#include "bag_fuzz_checks.h"
#include "swlio/drivers/bag/mcap_reader.h"

namespace swlio::fuzz {

int FuzzMcap(const uint8_t* data, size_t size) {
  std::string error;
  auto reader =
      drivers::bag::McapReader::OpenBytes({data, size}, "fuzz.mcap", FuzzLimits(), &error);
  if (!reader) {
    Check(!error.empty());
    return 0;
  }
  ReadToEnd(*reader, true);
  return 0;
}

}  // namespace swlio::fuzz

#ifndef SWLIO_FUZZ_NO_MAIN
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return swlio::fuzz::FuzzMcap(data, size);
}
#endif
