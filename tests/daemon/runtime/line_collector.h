#pragma once
// The lines of a child process (swlio-fastdds-echo), read on a thread of their own while a live
// drive runs, each split into its first word and `key=value` tokens.

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../../ipc/child_process.h"

namespace swlio::daemon::test {

using ipc::test_util::ChildProcess;

/// The `key=value` tokens of one --tf-check line (tools/fastdds-echo/tf_check.h), after its
/// first word.
struct Line {
  std::string kind;
  std::map<std::string, std::string> values;
  double Get(const std::string& key) const {
    const auto it = values.find(key);
    return it == values.end() ? std::nan("") : std::stod(it->second);
  }
  int64_t Int(const std::string& key) const {
    const auto it = values.find(key);
    return it == values.end() ? 0 : std::stoll(it->second);
  }
};

inline Line Parse(const std::string& text) {
  std::istringstream in(text);
  Line line;
  in >> line.kind;
  std::string token;
  while (in >> token) {
    const auto eq = token.find('=');
    if (eq != std::string::npos) line.values[token.substr(0, eq)] = token.substr(eq + 1);
  }
  return line;
}

/// Reads the child's lines on a thread of its own while the drive runs: a full pipe would
/// block the reader process, whose DDS readers would then drop samples.
class LineCollector {
 public:
  /// Keeps the lines in `path` too (for a look after a failure).
  LineCollector(ChildProcess* child, std::filesystem::path path)
      : path_(std::move(path)), thread_([this, child] {
          std::string text;
          std::ofstream keep(path_);
          while (!stop_) {
            if (!child->ReadLine(&text, 0.2)) {  // quiet, or the child has gone (EOF)
              std::this_thread::sleep_for(std::chrono::milliseconds(10));
              continue;
            }
            keep << text << "\n";
            std::lock_guard<std::mutex> lock(mutex_);
            lines_.push_back(Parse(text));
          }
        }) {}
  ~LineCollector() { Stop(); }
  std::vector<Line> Stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
    std::lock_guard<std::mutex> lock(mutex_);
    return lines_;
  }

 private:
  std::filesystem::path path_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::vector<Line> lines_;
  std::thread thread_;
};

}  // namespace swlio::daemon::test
