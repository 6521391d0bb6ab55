#include "swlio/daemon/config/config_files.h"

#include <gtest/gtest.h>

#include <fstream>

#include "swlio/daemon/config/config_loader.h"
#include "test_data.h"

namespace swlio::daemon {
namespace {

TEST(CheckReferencedFiles, ShippedConfigIsComplete) {
  const LoadedConfig loaded = LoadConfigFile(test::SourceDir() / "config" / "swlio.yaml");
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorReport();
  EXPECT_TRUE(CheckReferencedFiles(loaded.config).empty());
}

TEST(CheckReferencedFiles, MissingDdsXmlIsReported) {
  DaemonConfig config;
  config.ipc.dds_config_file = (test::MakeTempDir("cfgfiles") / "absent.xml").string();
  const auto problems = CheckReferencedFiles(config);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("cannot read"), std::string::npos) << problems[0];
  EXPECT_NE(problems[0].find("absent.xml"), std::string::npos) << problems[0];
}

TEST(CheckReferencedFiles, NonLoopbackXmlIsReportedOnlyWhenLoopbackIsRequired) {
  const auto path = test::MakeTempDir("cfgfiles") / "external.xml";
  std::ofstream(path) << "<CycloneDDS><Domain><General><Interfaces>"
                         "<NetworkInterface name=\"eth0\"/></Interfaces></General></Domain>"
                         "</CycloneDDS>\n";
  DaemonConfig config;
  config.ipc.dds_config_file = path.string();
  config.ipc.require_loopback = true;
  const auto problems = CheckReferencedFiles(config);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("not loopback-only"), std::string::npos) << problems[0];
  config.ipc.require_loopback = false;
  EXPECT_TRUE(CheckReferencedFiles(config).empty());
}

TEST(CheckReferencedFiles, DdsSecurityFilesAndDomainAreChecked) {
  const auto dir = test::MakeTempDir("cfgfiles");
  std::ofstream(dir / "ca.pem") << "not checked here: the plugins read it\n";
  const auto path = dir / "secure.xml";
  std::ofstream(path) << "<CycloneDDS><Domain><Security><Authentication>"
                         "<IdentityCA>file:"
                      << (dir / "ca.pem").string()
                      << "</IdentityCA><PrivateKey>file:" << (dir / "key.pem").string()
                      << "</PrivateKey></Authentication></Security></Domain></CycloneDDS>\n";
  DaemonConfig config;
  config.ipc.dds_config_file = path.string();
  config.ipc.require_loopback = false;
  config.ipc.domain_id = 231;
  const auto problems = CheckReferencedFiles(config);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_NE(
      problems[0].find("the PrivateKey file '" + (dir / "key.pem").string() + "' is not readable"),
      std::string::npos)
      << problems[0];
  EXPECT_NE(problems[1].find("ipc.domain_id: 231"), std::string::npos) << problems[1];
  std::ofstream(dir / "key.pem") << "\n";
  config.ipc.domain_id = 230;
  EXPECT_TRUE(CheckReferencedFiles(config).empty());
}

}  // namespace
}  // namespace swlio::daemon
