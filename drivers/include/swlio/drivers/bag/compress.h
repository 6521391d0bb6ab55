#pragma once
/// @file
/// Chunk compression for bag writers (MCAP export; ROS 1 bags in tests), the inverse of
/// decompress.h: zstd frames with the content size recorded (libzstd ZSTD_compress), LZ4 frame
/// streams (liblz4 LZ4F_compressFrame) and bzip2 streams (libbz2, block size 9 as rosbag writes).

#include <cstdint>
#include <span>
#include <vector>

#include "swlio/drivers/bag/decompress.h"

namespace swlio::drivers::bag {

/// Compresses `in` into `out`; false only when the library fails (out of memory).
/// `zstd_level`: 1 (fast) … 19 (small); ignored by the other formats.
bool Compress(Compression compression,
              std::span<const uint8_t> in,
              std::vector<uint8_t>* out,
              int zstd_level = 1);

}  // namespace swlio::drivers::bag
