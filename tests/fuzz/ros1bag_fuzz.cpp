// libFuzzer target: the ROS 1 bag reader on arbitrary file bytes (bag_fuzz_checks.h
// invariants). Seeds: tests/fuzz/corpus/ros1bag and, in scripts/fuzz, bags written by
// make_bag_seeds from the real .db3 bags' messages (re-serialized as ROS 1).

#include <string>

#include "bag_fuzz_checks.h"
#include "swlio/drivers/bag/ros1_bag_reader.h"

namespace swlio::fuzz {

int FuzzRos1Bag(const uint8_t* data, size_t size) {
  std::string error;
  auto reader =
      drivers::bag::Ros1BagReader::OpenBytes({data, size}, "fuzz.bag", FuzzLimits(), &error);
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
  return swlio::fuzz::FuzzRos1Bag(data, size);
}
#endif
