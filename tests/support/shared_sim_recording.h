#pragma once
/// @file
/// A simulated recording shared by the tests of one test program. ctest runs every test in its
/// own process, so a fixture's SetUpTestSuite used to write the same recording once per test
/// (25–30 s of drive, seconds each, more under the sanitizers). This writes it once per
/// (scenario, seed, duration) and program build, under
/// <tmp>/swlio-test-recordings/<program>-<hash of its path>/, and every later process reuses it.
/// - Keyed by the program's modification time: a rebuilt program (and the simulator it links)
///   never reads an older recording; the older ones of the same key are removed.
/// - Written into a private folder and renamed into place: parallel tests never see half of one.
/// - Read only: tests write their outputs elsewhere (test::MakeTempDir).
/// Only for test programs that link swlio_sim.

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <system_error>

#include "recording/sim_recording.h"
#include "scenarios/sim_setup.h"

namespace swlio::test {

/// The recording's folder, or empty (with `error` set) when it could not be written.
inline std::filesystem::path SharedSimRecording(const std::string& scenario,
                                                uint64_t seed,
                                                double duration_s,
                                                std::string* error) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  const auto stamp = fs::last_write_time(program, ec).time_since_epoch().count();
  const fs::path root = fs::temp_directory_path() / "swlio-test-recordings" /
                        (program.filename().string() + "-" +
                         std::to_string(std::hash<std::string>{}(program.string())));
  const std::string key = scenario + "_" + std::to_string(seed) + "_" +
                          std::to_string(std::llround(duration_s * 1000.0)) + "ms_";
  const fs::path dir = root / (key + std::to_string(stamp));
  if (fs::exists(dir, ec)) return dir;  // complete: only a finished recording is renamed there
  fs::create_directories(root, ec);
  for (const fs::directory_entry& e : fs::directory_iterator(root, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(key, 0) == 0 && name.find(".tmp") == std::string::npos) {
      fs::remove_all(e.path(), ec);  // an older build's
    }
  }
  const fs::path tmp = fs::path(dir.string() + ".tmp" + std::to_string(::getpid()));
  fs::remove_all(tmp, ec);
  const auto setup = sim::MakeSimSetup(scenario, seed, duration_s);
  sim::RecordingStats stats;
  if (!setup || !sim::WriteRecording(*setup, tmp, &stats, error)) {
    fs::remove_all(tmp, ec);
    return {};
  }
  fs::rename(tmp, dir, ec);  // fails when another process was first: its copy is complete
  if (ec) fs::remove_all(tmp, ec);
  return dir;
}

}  // namespace swlio::test
