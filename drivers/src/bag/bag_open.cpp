// Format detection and opening of bag files and rosbag2 folders (bag_open.h).

#include "swlio/drivers/bag/bag_open.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <vector>

#include "swlio/drivers/bag/mcap_reader.h"
#include "swlio/drivers/bag/mcap_records.h"
#include "swlio/drivers/bag/merged_bag_reader.h"
#include "swlio/drivers/bag/ros1_bag_reader.h"
#include "swlio/drivers/bag/rosbag2_metadata.h"
#include "swlio/drivers/bag/rosbag2_sqlite_reader.h"

namespace swlio::drivers::bag {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kSqliteMagic{"SQLite format 3\0", 16};
constexpr std::string_view kRos1Magic = "#ROSBAG V";
constexpr size_t kHeadBytes = 16;

bool StartsWith(std::span<const uint8_t> head, std::string_view magic) {
  return head.size() >= magic.size() &&
         std::equal(magic.begin(), magic.end(), head.begin(),
                    [](char a, uint8_t b) { return uint8_t(a) == b; });
}

bool EndsWith(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// Natural order: digit runs compare as numbers, so bag_2.db3 sorts before bag_10.db3.
bool NaturalLess(const std::string& a, const std::string& b) {
  size_t i = 0;
  size_t j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) &&
        std::isdigit(static_cast<unsigned char>(b[j]))) {
      size_t ie = i;
      size_t je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      const std::string na = a.substr(i, ie - i);
      const std::string nb = b.substr(j, je - j);
      if (na.size() != nb.size()) return na.size() < nb.size();
      if (na != nb) return na < nb;
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

std::vector<uint8_t> Head(const std::string& path) {
  std::vector<uint8_t> head(kHeadBytes);
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(std::max<std::streamsize>(0, in.gcount())));
  return head;
}

/// rosbag2's compression as its metadata.yaml beside `file` states it (none when absent).
Rosbag2Metadata SiblingMetadata(const fs::path& file) {
  Rosbag2Metadata m;
  std::string ignored;
  const fs::path yaml = file.parent_path() / "metadata.yaml";
  if (fs::exists(yaml)) ReadRosbag2Metadata(yaml, &m, &ignored);
  return m;
}

std::unique_ptr<BagReader> OpenFile(const std::string& path,
                                    const BagReadLimits& limits,
                                    std::string* error) {
  if (!fs::exists(path)) {
    *error = path + ": no such file or folder";
    return nullptr;
  }
  if (EndsWith(path, ".zstd")) {
    *error = path + ": a file-compressed rosbag2 bag; decompress it first (zstd -d '" + path + "')";
    return nullptr;
  }
  const Rosbag2Metadata meta = SiblingMetadata(path);
  const bool per_message = Lower(meta.compression_mode) == "message";
  switch (DetectBagFormat(Head(path), path)) {
    case BagFormat::kRosbag2Sqlite: {
      if (per_message && meta.compression_format != "zstd") {
        *error = path + ": rosbag2 message compression '" + meta.compression_format +
                 "' is not supported (zstd is)";
        return nullptr;
      }
      Rosbag2SqliteOptions options;
      options.zstd_per_message = per_message;
      options.limits = limits;
      return Rosbag2SqliteReader::Open(path, options, error);
    }
    case BagFormat::kMcap:
      if (per_message) {
        *error = path + ": rosbag2 per-message compression in MCAP storage is not supported";
        return nullptr;
      }
      return McapReader::Open(path, limits, error);
    case BagFormat::kRos1:
      return Ros1BagReader::Open(path, limits, error);
    case BagFormat::kUnknown:
      break;
  }
  *error = path + ": not a bag (expected rosbag2 .db3, MCAP or ROS 1 .bag)";
  return nullptr;
}

/// The storage files of a rosbag2 folder, in recording order.
bool FolderFiles(const fs::path& dir, std::vector<std::string>* files, std::string* error) {
  const fs::path yaml = dir / "metadata.yaml";
  Rosbag2Metadata meta;
  if (fs::exists(yaml) && !ReadRosbag2Metadata(yaml, &meta, error)) return false;
  if (Lower(meta.compression_mode) == "file") {
    *error = dir.string() + ": a file-compressed rosbag2 bag; decompress its files first (zstd -d)";
    return false;
  }
  for (const std::string& f : meta.relative_file_paths) files->push_back((dir / f).string());
  if (!files->empty()) return true;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (EndsWith(name, ".db3") || EndsWith(name, ".mcap")) files->push_back(e.path().string());
  }
  std::sort(files->begin(), files->end(), NaturalLess);
  if (files->empty()) *error = dir.string() + ": a folder without .db3 or .mcap files";
  return !files->empty();
}

std::unique_ptr<BagReader> OpenFolder(const std::string& dir,
                                      const BagReadLimits& limits,
                                      std::string* error) {
  std::vector<std::string> files;
  if (!FolderFiles(dir, &files, error)) return nullptr;
  std::vector<std::unique_ptr<BagReader>> parts;
  for (const std::string& f : files) {
    auto reader = OpenFile(f, limits, error);
    if (!reader) return nullptr;
    parts.push_back(std::move(reader));
  }
  if (parts.size() == 1) return std::move(parts.front());
  return std::make_unique<MergedBagReader>(dir, std::move(parts));
}

}  // namespace

BagFormat DetectBagFormat(std::span<const uint8_t> head, std::string_view path) {
  if (StartsWith(head, kSqliteMagic)) return BagFormat::kRosbag2Sqlite;
  if (StartsWith(head, {reinterpret_cast<const char*>(mcap::kMagic.data()), mcap::kMagic.size()})) {
    return BagFormat::kMcap;
  }
  if (StartsWith(head, kRos1Magic)) return BagFormat::kRos1;
  if (head.size() >= mcap::kMagic.size()) return BagFormat::kUnknown;
  // Too short to tell by content (an empty or cut file): the readers will say what is wrong.
  if (EndsWith(path, ".db3")) return BagFormat::kRosbag2Sqlite;
  if (EndsWith(path, ".mcap")) return BagFormat::kMcap;
  if (EndsWith(path, ".bag")) return BagFormat::kRos1;
  return BagFormat::kUnknown;
}

std::unique_ptr<BagReader> OpenBag(const std::string& path,
                                   const BagReadLimits& limits,
                                   std::string* error) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) return OpenFolder(path, limits, error);
  return OpenFile(path, limits, error);
}

}  // namespace swlio::drivers::bag
