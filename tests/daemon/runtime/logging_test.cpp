#include "swlio/daemon/runtime/logging.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test_data.h"

namespace swlio::daemon {
namespace {

std::string ReadFile(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Logging, WritesFileWithLevelFilter) {
  LoggingConfig config;
  config.directory = (test::MakeTempDir("log") / "nested").string();  // created on demand
  config.file_level = "info";
  config.stderr_level = "off";
  std::string error;
  auto logger = SetupLogging(config, &error);
  ASSERT_NE(logger, nullptr) << error;
  logger->info("lidar packets={} drops={}", 7500, 0);
  logger->debug("this is below the file level");
  logger->flush();
  const std::string text = ReadFile(std::filesystem::path(config.directory) / "swliod.log");
  EXPECT_NE(text.find("info  ["), std::string::npos) << text;
  EXPECT_NE(text.find("lidar packets=7500 drops=0"), std::string::npos);
  EXPECT_EQ(text.find("below the file level"), std::string::npos);
}

TEST(Logging, RotatesAtTheConfiguredSize) {
  LoggingConfig config;
  const auto dir = test::MakeTempDir("logrot");
  config.directory = dir.string();
  config.stderr_level = "off";
  config.max_file_size_mb = 1;
  config.max_files = 2;
  std::string error;
  auto logger = SetupLogging(config, &error);
  ASSERT_NE(logger, nullptr) << error;
  const std::string line(200, 'x');
  for (int i = 0; i < 15000; ++i) logger->info("{} {}", i, line);  // ≈ 3.3 MB
  logger->flush();
  EXPECT_TRUE(std::filesystem::exists(dir / "swliod.log"));
  EXPECT_TRUE(std::filesystem::exists(dir / "swliod.1.log"));
  EXPECT_TRUE(std::filesystem::exists(dir / "swliod.2.log"));
  EXPECT_FALSE(std::filesystem::exists(dir / "swliod.3.log"));  // max_files bounds disk use
  EXPECT_LE(std::filesystem::file_size(dir / "swliod.1.log"), 1024u * 1024u);
}

TEST(Logging, UnwritableDirectoryIsAnError) {
  const auto dir = test::MakeTempDir("logbad");
  std::ofstream(dir / "file") << "x";
  LoggingConfig config;
  config.directory = (dir / "file").string();  // a file, not a directory
  std::string error;
  EXPECT_EQ(SetupLogging(config, &error), nullptr);
  EXPECT_NE(error.find("cannot open log file"), std::string::npos) << error;
}

}  // namespace
}  // namespace swlio::daemon
