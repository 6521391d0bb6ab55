// The bag fuzz targets (tests/fuzz/{mcap,ros1bag,rosbag2,bag_message}_fuzz.cpp, linked into
// this program without libFuzzer's main) on their kept corpora: their invariants hold in every
// test build (Release, ASan+UBSan) without clang. A violated invariant traps.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "test_data.h"

namespace swlio::fuzz {
int FuzzMcap(const uint8_t* data, size_t size);
int FuzzRos1Bag(const uint8_t* data, size_t size);
int FuzzRosbag2(const uint8_t* data, size_t size);
int FuzzBagMessage(const uint8_t* data, size_t size);
}  // namespace swlio::fuzz

namespace {

using Target = int (*)(const uint8_t*, size_t);

std::vector<uint8_t> ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs `target` on every kept input of `corpus`, whole and cut in half.
size_t RunCorpus(const std::string& corpus, Target target) {
  const auto dir = swlio::test::SourceDir() / "tests/fuzz/corpus" / corpus;
  size_t n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    SCOPED_TRACE(e.path().string());
    const std::vector<uint8_t> bytes = ReadBytes(e.path());
    EXPECT_EQ(target(bytes.data(), bytes.size()), 0);
    EXPECT_EQ(target(bytes.data(), bytes.size() / 2), 0);
    ++n;
  }
  return n;
}

TEST(BagFuzzCorpus, McapKeepsItsInvariants) {
  EXPECT_GE(RunCorpus("mcap", swlio::fuzz::FuzzMcap), 4u);
}

TEST(BagFuzzCorpus, Ros1BagKeepsItsInvariants) {
  EXPECT_GE(RunCorpus("ros1bag", swlio::fuzz::FuzzRos1Bag), 6u);
}

TEST(BagFuzzCorpus, Rosbag2KeepsItsInvariants) {
  EXPECT_GE(RunCorpus("rosbag2", swlio::fuzz::FuzzRosbag2), 1u);
}

TEST(BagFuzzCorpus, MessageDecodersKeepTheirInvariants) {
  EXPECT_GE(RunCorpus("bag_message", swlio::fuzz::FuzzBagMessage), 20u);
}

}  // namespace
