// ReplaceFile (common/replace_file.h): a file written whole or not at all.

#include "swlio/estimator/common/replace_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_data.h"

namespace swlio::estimator {
namespace {

using ::testing::HasSubstr;

std::string Read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// `text` written to `path` through ReplaceFile.
bool Put(const std::string& path, const std::string& text, std::string* error) {
  return ReplaceFile(
      path, "state",
      [&text](std::ostream& out, std::string*) { return static_cast<bool>(out << text); }, error);
}

TEST(ReplaceFile, WritesAndReplacesWholeLeavingNoTemporary) {
  const auto dir = test::MakeTempDir("replace_file");
  const std::string path = (dir / "state.txt").string();
  std::string error;
  ASSERT_TRUE(Put(path, "first\n", &error)) << error;
  EXPECT_EQ(Read(path), "first\n");
  ASSERT_TRUE(Put(path, "second\n", &error)) << error;
  EXPECT_EQ(Read(path), "second\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(ReplaceFile, AWriterThatGivesUpLeavesTheOldFile) {
  const auto dir = test::MakeTempDir("replace_file");
  const std::string path = (dir / "state.txt").string();
  std::string error;
  ASSERT_TRUE(Put(path, "kept\n", &error)) << error;
  EXPECT_FALSE(ReplaceFile(
      path, "state",
      [](std::ostream& out, std::string* why) {
        out << "half of it";
        *why = "state: the writer gave up";
        return false;
      },
      &error));
  EXPECT_EQ(error, "state: the writer gave up");
  EXPECT_EQ(Read(path), "kept\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(ReplaceFile, AMissingDirectorySaysWhichStepFailed) {
  const auto dir = test::MakeTempDir("replace_file");
  const std::string path = (dir / "no" / "such.txt").string();
  std::string error;
  EXPECT_FALSE(Put(path, "x", &error));
  EXPECT_THAT(error, HasSubstr("state: cannot create " + path + ".tmp: "));
  // A directory where the file should be: the rename fails, the temporary goes.
  const std::string blocked = (dir / "blocked").string();
  std::filesystem::create_directories(std::filesystem::path(blocked) / "inside");
  EXPECT_FALSE(Put(blocked, "x", &error));
  EXPECT_THAT(error, HasSubstr("state: renaming " + blocked + ".tmp to " + blocked + " failed"));
  EXPECT_FALSE(std::filesystem::exists(blocked + ".tmp"));
  EXPECT_FALSE(Put(path, "x", nullptr));  // no error text asked for
}

}  // namespace
}  // namespace swlio::estimator
