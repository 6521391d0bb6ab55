#pragma once
/// @file
/// Where tests find real captures and the source tree.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace swlio::test {

/// `$SWLIO_DATA_DIR`, else `../shared/data` beside the checkout. May not exist.
std::filesystem::path DataDir();

/// Path of `relative` under DataDir(), or empty when it does not exist.
std::filesystem::path DataFile(const std::string& relative);

/// The checkout's root (for config/ and other checked-in files).
std::filesystem::path SourceDir();

/// A fresh empty directory under the system temp dir, unique per call; removed with everything
/// in it when the test process exits (SWLIO_KEEP_TEST_DIRS=1 keeps it).
std::filesystem::path MakeTempDir(const std::string& tag);

/// A program built next to the running test (build/bin/<name>), or empty when absent.
std::filesystem::path ToolPath(const std::string& name);

/// Runs `command` with /bin/sh; returns stdout (append "2>&1" for stderr). `exit_code`
/// (optional) receives the exit status, or -1 when it did not exit normally.
std::string RunCommand(const std::string& command, int* exit_code = nullptr);

}  // namespace swlio::test

/// Skips the current test with a clear message when a real-data file is absent.
#define SWLIO_REQUIRE_DATA(var, relative)                                                   \
  const std::filesystem::path var = ::swlio::test::DataFile(relative);                      \
  if (var.empty()) {                                                                        \
    GTEST_SKIP() << "real data '" << (relative) << "' not found under "                     \
                 << ::swlio::test::DataDir() << " (set SWLIO_DATA_DIR to the shared data)"; \
  }
