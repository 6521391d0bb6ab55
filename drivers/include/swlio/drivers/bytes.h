#pragma once
/// @file
/// Explicit-endian field access for wire formats. Fields are never read by casting a struct
/// over a buffer: every read names its byte order. Callers check lengths before reading.

#include <bit>
#include <cstdint>
#include <cstring>

namespace swlio::drivers::bytes {

inline uint16_t ReadU16Le(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
inline uint16_t ReadU16Be(const uint8_t* p) { return static_cast<uint16_t>((p[0] << 8) | p[1]); }
inline uint32_t ReadU32Le(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
         (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
}
inline uint32_t ReadU32Be(const uint8_t* p) {
  return (static_cast<uint32_t>(p[0]) << 24) | (static_cast<uint32_t>(p[1]) << 16) |
         (static_cast<uint32_t>(p[2]) << 8) | static_cast<uint32_t>(p[3]);
}
inline uint64_t ReadU64Le(const uint8_t* p) {
  return static_cast<uint64_t>(ReadU32Le(p)) | (static_cast<uint64_t>(ReadU32Le(p + 4)) << 32);
}
inline uint64_t ReadU64Be(const uint8_t* p) {
  return (static_cast<uint64_t>(ReadU32Be(p)) << 32) | static_cast<uint64_t>(ReadU32Be(p + 4));
}
/// Unsigned big-endian integer of 1 to 8 bytes (e.g. 48-bit fields).
inline uint64_t ReadUBe(const uint8_t* p, int n) {
  uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}
inline int16_t ReadI16Le(const uint8_t* p) { return static_cast<int16_t>(ReadU16Le(p)); }
inline int16_t ReadI16Be(const uint8_t* p) { return static_cast<int16_t>(ReadU16Be(p)); }
inline int32_t ReadI32Le(const uint8_t* p) { return static_cast<int32_t>(ReadU32Le(p)); }
inline int32_t ReadI32Be(const uint8_t* p) { return static_cast<int32_t>(ReadU32Be(p)); }
inline int64_t ReadI64Be(const uint8_t* p) { return static_cast<int64_t>(ReadU64Be(p)); }
inline float ReadF32Be(const uint8_t* p) { return std::bit_cast<float>(ReadU32Be(p)); }
inline float ReadF32Le(const uint8_t* p) { return std::bit_cast<float>(ReadU32Le(p)); }
inline double ReadF64Be(const uint8_t* p) { return std::bit_cast<double>(ReadU64Be(p)); }
inline double ReadF64Le(const uint8_t* p) { return std::bit_cast<double>(ReadU64Le(p)); }

inline void WriteU16Le(uint8_t* p, uint16_t v) {
  p[0] = static_cast<uint8_t>(v);
  p[1] = static_cast<uint8_t>(v >> 8);
}
inline void WriteU16Be(uint8_t* p, uint16_t v) {
  p[0] = static_cast<uint8_t>(v >> 8);
  p[1] = static_cast<uint8_t>(v);
}
inline void WriteU32Le(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
inline void WriteU32Be(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (24 - 8 * i));
}
inline void WriteU64Be(uint8_t* p, uint64_t v) {
  WriteU32Be(p, static_cast<uint32_t>(v >> 32));
  WriteU32Be(p + 4, static_cast<uint32_t>(v));
}
/// Unsigned big-endian integer of 1 to 8 bytes.
inline void WriteUBe(uint8_t* p, uint64_t v, int n) {
  for (int i = n - 1; i >= 0; --i) {
    p[i] = static_cast<uint8_t>(v);
    v >>= 8;
  }
}
inline void WriteF32Be(uint8_t* p, float v) { WriteU32Be(p, std::bit_cast<uint32_t>(v)); }
inline void WriteF64Be(uint8_t* p, double v) { WriteU64Be(p, std::bit_cast<uint64_t>(v)); }

}  // namespace swlio::drivers::bytes
