#pragma once
/// @file
/// FNV-1a, 64-bit (Fowler–Noll–Vo; offset basis 0xcbf29ce484222325, prime 0x100000001b3, as in
/// the published FNV reference): a fast, non-cryptographic digest of bytes. The saved map's
/// checksum (estimator/map-format.md) and the map cloud's digest in swlio-fastdds-echo.

#include <cstdint>
#include <string_view>

namespace swlio {

inline constexpr uint64_t kFnv1a64OffsetBasis = 0xcbf29ce484222325ULL;
inline constexpr uint64_t kFnv1a64Prime = 0x100000001b3ULL;

/// FNV-1a 64 of `bytes`, continuing from `hash` (the offset basis for a fresh digest).
constexpr uint64_t Fnv1a64(std::string_view bytes, uint64_t hash = kFnv1a64OffsetBasis) {
  for (const char b : bytes) hash = (hash ^ static_cast<unsigned char>(b)) * kFnv1a64Prime;
  return hash;
}

}  // namespace swlio
