// CRC-32 through zlib (see crc32.h for the definition MCAP uses).

#include "swlio/drivers/bag/crc32.h"

#include <zlib.h>

#include <algorithm>
#include <limits>

namespace swlio::drivers::bag {

uint32_t Crc32Update(uint32_t crc, std::span<const uint8_t> bytes) {
  uLong c = crc;
  constexpr size_t kMaxPiece = std::numeric_limits<uInt>::max();
  while (!bytes.empty()) {
    const size_t n = std::min(bytes.size(), kMaxPiece);
    c = crc32(c, bytes.data(), static_cast<uInt>(n));
    bytes = bytes.subspan(n);
  }
  return static_cast<uint32_t>(c);
}

}  // namespace swlio::drivers::bag
