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

bool Writes(const std::string& text, std::ostream& out) { return static_cast<bool>(out << text); }

TEST(ReplaceFile, WritesAndReplacesWholeLeavingNoTemporary) {
  const auto dir = test::MakeTempDir("replace_file");
  const std::string path = (dir / "state.txt").string();
  std::string error;
  ASSERT_TRUE(ReplaceFile(
      path, "state", [](std::ostream& out, std::string*) { return Writes("first\n", out); },
      &error))
      << error;
  EXPECT_EQ(Read(path), "first\n");
  ASSERT_TRUE(ReplaceFile(
      path, "state", [](std::ostream& out, std::string*) { return Writes("second\n", out); },
      &error))
      << error;
  EXPECT_EQ(Read(path), "second\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(ReplaceFile, AWriterThatGivesUpLeavesTheOldFile) {
  const auto dir = test::MakeTempDir("replace_file");
  const std::string path = (dir / "state.txt").string();
  std::string error;
  ASSERT_TRUE(ReplaceFile(
      path, "state", [](std::ostream& out, std::string*) { return Writes("kept\n", out); },
      &error));
  EXPECT_FALSE(ReplaceFile(
      path, "state",
      [](std::ostream& out, std::string* why) {
        Writes("half of it", out);
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
  EXPECT_FALSE(ReplaceFile(
      path, "state", [](std::ostream& out, std::string*) { return Writes("x", out); }, &error));
  EXPECT_THAT(error, HasSubstr("state: cannot create " + path + ".tmp: "));
  // A directory where the file should be: the rename fails, the temporary goes.
  const std::string blocked = (dir / "blocked").string();
  std::filesystem::create_directories(std::filesystem::path(blocked) / "inside");
  EXPECT_FALSE(ReplaceFile(
      blocked, "state", [](std::ostream& out, std::string*) { return Writes("x", out); }, &error));
  EXPECT_THAT(error, HasSubstr("state: renaming " + blocked + ".tmp to " + blocked + " failed"));
  EXPECT_FALSE(std::filesystem::exists(blocked + ".tmp"));
  EXPECT_FALSE(ReplaceFile(
      path, "state", [](std::ostream& out, std::string*) { return Writes("x", out); }, nullptr));
}

}  // namespace
}  // namespace swlio::estimator
