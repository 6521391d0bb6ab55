#include "../../tools/decode/json_writer.h"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <sstream>

namespace swlio::tools {
namespace {

TEST(JsonWriter, NestedObjectsArraysAndEscapes) {
  std::ostringstream os;
  JsonWriter j(os);
  const std::array<uint16_t, 3> ring = {0, 15, 8};
  j.BeginObject();
  j.Key("n").Value(uint64_t{3});
  j.Key("byte").Value(uint8_t{7});
  j.Key("neg").Value(-2);
  j.Key("x").Value(0.25);
  j.Key("nan").Value(std::numeric_limits<double>::quiet_NaN());
  j.Key("ok").Value(true);
  j.Key("s").Value("a\"b\\c\n");
  j.Key("ring").Array(std::span<const uint16_t>(ring));
  j.Key("empty").BeginArray().EndArray();
  j.Key("o").BeginObject().Key("k").Value("v").EndObject();
  j.EndObject();
  EXPECT_EQ(os.str(),
            R"({"n":3,"byte":7,"neg":-2,"x":0.25,"nan":null,"ok":true,"s":"a\"b\\c\u000a",)"
            R"("ring":[0,15,8],"empty":[],"o":{"k":"v"}})");
}

}  // namespace
}  // namespace swlio::tools
