#include "swlio/ipc/participant.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test_data.h"

namespace swlio::ipc {
namespace {

std::string ShippedXml() {
  std::ifstream in(test::SourceDir() / "config" / "cyclonedds-loopback.xml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

TEST(LoopbackConfig, ShippedXmlIsLoopbackOnly) {
  std::string why;
  EXPECT_TRUE(IsLoopbackOnlyConfig(ShippedXml(), &why)) << why;
}

TEST(LoopbackConfig, RejectsEveryWayOfLeavingLoopback) {
  const std::string xml = ShippedXml();
  std::string why;
  EXPECT_FALSE(IsLoopbackOnlyConfig(Replace(xml, "name=\"lo\"", "name=\"eth0\""), &why));
  EXPECT_NE(why.find("not loopback"), std::string::npos);
  EXPECT_FALSE(
      IsLoopbackOnlyConfig(Replace(xml, "<AllowMulticast>false", "<AllowMulticast>true"), &why));
  EXPECT_NE(why.find("AllowMulticast"), std::string::npos);
  EXPECT_FALSE(IsLoopbackOnlyConfig(Replace(xml, "<NetworkInterface name=\"lo\"/>", ""), &why));
  EXPECT_NE(why.find("no NetworkInterface"), std::string::npos);
  EXPECT_FALSE(IsLoopbackOnlyConfig(
      Replace(xml, "<Peer address=\"127.0.0.1\"/>", "<Peer address=\"10.0.0.5\"/>"), &why));
  EXPECT_FALSE(IsLoopbackOnlyConfig("<CycloneDDS/>", &why));
}

IpcConfig TestConfig(int64_t domain) {
  IpcConfig config;
  config.domain_id = domain;
  config.dds_config_file = (test::SourceDir() / "config" / "cyclonedds-loopback.xml").string();
  return config;
}

TEST(Participant, CreatesFromLoopbackConfigAndSharesTheDomain) {
  std::string error;
  auto a = Participant::Create(TestConfig(101), &error);
  ASSERT_NE(a, nullptr) << error;
  auto b = Participant::Create(TestConfig(101), &error);
  ASSERT_NE(b, nullptr) << error;
  EXPECT_GT(a->handle(), 0);
  EXPECT_NE(a->handle(), b->handle());
  EXPECT_EQ(b->domain_id(), 101u);
}

TEST(Participant, RefusesNonLoopbackOrMissingConfig) {
  const auto dir = test::MakeTempDir("dds");
  const auto bad = dir / "eth.xml";
  std::ofstream(bad) << Replace(ShippedXml(), "name=\"lo\"", "name=\"eth0\"");
  IpcConfig config = TestConfig(102);
  config.dds_config_file = bad.string();
  std::string error;
  EXPECT_EQ(Participant::Create(config, &error), nullptr);
  EXPECT_NE(error.find("refusing to start DDS"), std::string::npos) << error;

  config.dds_config_file = (dir / "missing.xml").string();
  EXPECT_EQ(Participant::Create(config, &error), nullptr);
  EXPECT_NE(error.find("cannot read"), std::string::npos) << error;
}

}  // namespace
}  // namespace swlio::ipc
