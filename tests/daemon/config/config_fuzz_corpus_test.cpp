// The configuration loader's fuzz target (tests/fuzz/config_fuzz.cpp, linked into this test
// program) on its kept corpus (tests/fuzz/corpus/config: inputs a libFuzzer run found
// interesting, minimized) and the shipped configuration: the fuzzer's invariants hold in every
// test build (Release, ASan+UBSan) without clang. A violated invariant traps (the test crashes).

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "test_data.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace swlio::daemon {
namespace {

std::vector<uint8_t> ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ConfigFuzzCorpus, EveryKeptInputKeepsTheLoadersInvariants) {
  const auto root = ::swlio::test::SourceDir();
  std::vector<std::filesystem::path> inputs = {root / "config" / "swlio.yaml"};
  for (const auto& e : std::filesystem::directory_iterator(root / "tests/fuzz/corpus/config")) {
    inputs.push_back(e.path());
  }
  ASSERT_GE(inputs.size(), 20u) << "the kept corpus is missing";
  for (const auto& path : inputs) {
    SCOPED_TRACE(path.string());
    const std::vector<uint8_t> bytes = ReadBytes(path);
    EXPECT_EQ(LLVMFuzzerTestOneInput(bytes.data(), bytes.size()), 0);
  }
}

}  // namespace
}  // namespace swlio::daemon
