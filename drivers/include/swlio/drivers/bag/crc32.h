#pragma once
/// @file
/// CRC-32 (IEEE 802.3: reflected polynomial 0xEDB88320, initial value and final XOR 0xFFFFFFFF),
/// the checksum MCAP uses for chunks, the data section and the summary
/// (foxglove/mcap website/docs/spec/index.md, "Chunk", "Data End", "Footer"). It is zlib's
/// crc32(); this wrapper only feeds spans larger than zlib's uInt in pieces.

#include <cstdint>
#include <span>

namespace swlio::drivers::bag {

/// Continues a running CRC (start with 0) over `bytes`.
uint32_t Crc32Update(uint32_t crc, std::span<const uint8_t> bytes);

inline uint32_t Crc32(std::span<const uint8_t> bytes) { return Crc32Update(0, bytes); }

}  // namespace swlio::drivers::bag
