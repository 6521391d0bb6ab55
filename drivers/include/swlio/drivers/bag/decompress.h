#pragma once
/// @file
/// Chunk decompression for the bag containers, through Debian's libraries: zstd frames
/// (libzstd), LZ4 *frame* streams (liblz4's lz4frame.h: MCAP's "lz4" and ROS 1's roslz4 are
/// both the frame format, not raw blocks) and bzip2 streams (libbz2, ROS 1 "bz2").
///
/// Every container states the uncompressed size, so each function decompresses into exactly
/// `expected_size` bytes and fails when the stream holds more, less or is damaged. The caller
/// bounds `expected_size` before calling (BagReadLimits::max_chunk_bytes).

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace swlio::drivers::bag {

enum class Compression : uint8_t { kNone, kZstd, kLz4Frame, kBz2 };

/// The compression a container names ("" or "none", "zstd", "lz4", "bz2"); false when unknown.
/// MCAP's names and ROS 1's are merged: neither container uses the other's.
bool ParseCompression(std::string_view name, Compression* out);

/// Decompresses `in` into `out` (resized to `expected_size`). On failure returns false and sets
/// `error` to a short reason ("zstd: Unknown frame descriptor", "lz4: 10 bytes more than the
/// stated 4096", …) without the file name, which the caller adds.
bool Decompress(Compression compression,
                std::span<const uint8_t> in,
                uint64_t expected_size,
                std::vector<uint8_t>* out,
                std::string* error);

}  // namespace swlio::drivers::bag
