#pragma once
/// @file
/// Opens any bag swlio reads, deciding the container from the file's first bytes (the
/// extension only decides when the bytes are inconclusive):
///   - SQLite3 ("SQLite format 3\0", sqlite.org/fileformat.html §1.3.1) → rosbag2 .db3;
///   - MCAP magic 89 4D 43 41 50 30 0D 0A → MCAP;
///   - "#ROSBAG V" → ROS 1 bag;
///   - a folder: a rosbag2 bag; its metadata.yaml (when present) names the storage files in
///     order, else every .db3 or .mcap file in it is taken in natural order (…_2 before …_10).
/// Several files are merged by receive time (MergedBagReader). rosbag2's compression: message
/// mode (zstd per message) is undone for .db3 files; file mode (.db3.zstd, .mcap.zstd) is
/// refused with a message saying how to decompress.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "swlio/drivers/bag/bag_reader.h"

namespace swlio::drivers::bag {

enum class BagFormat : uint8_t { kRosbag2Sqlite, kMcap, kRos1, kUnknown };

/// The container of a file from its first bytes (≥ 16 when the file has them), else from the
/// extension of `path` (.db3, .mcap, .bag).
BagFormat DetectBagFormat(std::span<const uint8_t> head, std::string_view path);

/// Opens a bag file or rosbag2 folder. Returns nullptr and sets `error` (naming the path) when
/// it is no bag, an unsupported variant, or unreadable.
std::unique_ptr<BagReader> OpenBag(const std::string& path,
                                   const BagReadLimits& limits,
                                   std::string* error);

}  // namespace swlio::drivers::bag
