#include "swlio/drivers/bytes.h"

#include <gtest/gtest.h>

#include <array>

namespace swlio::drivers::bytes {
namespace {

TEST(Bytes, ReadsBothByteOrders) {
  const std::array<uint8_t, 8> b = {0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08};
  EXPECT_EQ(ReadU16Le(b.data()), 0x0201);
  EXPECT_EQ(ReadU16Be(b.data()), 0x0102);
  EXPECT_EQ(ReadU32Le(b.data()), 0x04030201u);
  EXPECT_EQ(ReadU32Be(b.data()), 0x01020304u);
  EXPECT_EQ(ReadU64Be(b.data()), 0x0102030405060708ull);
  EXPECT_EQ(ReadU64Le(b.data()), 0x0807060504030201ull);
  EXPECT_EQ(ReadUBe(b.data(), 6), 0x010203040506ull);
}

TEST(Bytes, SignedAndFloatRoundTrip) {
  std::array<uint8_t, 8> b{};
  WriteU16Be(b.data(), 0xFFFE);
  EXPECT_EQ(ReadI16Be(b.data()), -2);
  WriteU16Le(b.data(), 0x8000);
  EXPECT_EQ(ReadI16Le(b.data()), -32768);
  WriteF32Be(b.data(), -9.81f);
  EXPECT_EQ(ReadF32Be(b.data()), -9.81f);
  WriteF64Be(b.data(), 3.141592653589793);
  EXPECT_EQ(ReadF64Be(b.data()), 3.141592653589793);
  WriteUBe(b.data(), 0xABCDEF, 3);
  EXPECT_EQ(ReadUBe(b.data(), 3), 0xABCDEFu);
  WriteU32Le(b.data(), 0xDEADBEEF);
  EXPECT_EQ(ReadI32Le(b.data()), static_cast<int32_t>(0xDEADBEEF));
}

}  // namespace
}  // namespace swlio::drivers::bytes
