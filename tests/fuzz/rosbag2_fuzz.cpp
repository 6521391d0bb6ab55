// libFuzzer target: the rosbag2 .db3 reader on arbitrary database images (SQLite parses them
// through sqlite3_deserialize; bag_fuzz_checks.h invariants, counts not exact: rows can be
// skipped while reading). Seeds: tests/fuzz/corpus/rosbag2 and, in scripts/fuzz, the real
// .db3 bags trimmed by make_seeds.py.

#include <string>

#include "bag_fuzz_checks.h"
#include "swlio/drivers/bag/rosbag2_sqlite_reader.h"

namespace swlio::fuzz {

int FuzzRosbag2(const uint8_t* data, size_t size) {
  std::string error;
  drivers::bag::Rosbag2SqliteOptions options;
  options.limits = FuzzLimits();
  options.zstd_per_message = size > 0 && (data[size - 1] & 1) != 0;
  auto reader =
      drivers::bag::Rosbag2SqliteReader::OpenBytes({data, size}, "fuzz.db3", options, &error);
  if (!reader) {
    Check(!error.empty());
    return 0;
  }
  ReadToEnd(*reader, false);
  return 0;
}

}  // namespace swlio::fuzz

#ifndef SWLIO_FUZZ_NO_MAIN
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return swlio::fuzz::FuzzRosbag2(data, size);
}
#endif
