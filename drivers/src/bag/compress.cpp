// Chunk compression through libzstd, liblz4 (frame API) and libbz2; see compress.h.

#include "swlio/drivers/bag/compress.h"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <climits>

namespace swlio::drivers::bag {
namespace {

constexpr int kBz2BlockSize100k = 9;  // rosbag's bz2_stream.cpp

bool CompressZstd(std::span<const uint8_t> in, std::vector<uint8_t>* out, int level) {
  out->resize(ZSTD_compressBound(in.size()));
  const size_t n = ZSTD_compress(out->data(), out->size(), in.data(), in.size(), level);
  if (ZSTD_isError(n)) return false;
  out->resize(n);
  return true;
}

bool CompressLz4Frame(std::span<const uint8_t> in, std::vector<uint8_t>* out) {
  LZ4F_preferences_t prefs{};
  prefs.frameInfo.contentSize = in.size();
  out->resize(LZ4F_compressFrameBound(in.size(), &prefs));
  const size_t n = LZ4F_compressFrame(out->data(), out->size(), in.data(), in.size(), &prefs);
  if (LZ4F_isError(n)) return false;
  out->resize(n);
  return true;
}

bool CompressBz2(std::span<const uint8_t> in, std::vector<uint8_t>* out) {
  if (in.size() > UINT_MAX / 2) return false;
  // libbz2's bound: 1% more plus 600 bytes.
  auto capacity = static_cast<unsigned int>(in.size() + in.size() / 100 + 600);
  out->resize(capacity);
  char* source = const_cast<char*>(reinterpret_cast<const char*>(in.data()));  // NOLINT: read only
  if (BZ2_bzBuffToBuffCompress(reinterpret_cast<char*>(out->data()), &capacity, source,
                               static_cast<unsigned int>(in.size()), kBz2BlockSize100k, 0,
                               0) != BZ_OK) {
    return false;
  }
  out->resize(capacity);
  return true;
}

}  // namespace

bool Compress(Compression compression,
              std::span<const uint8_t> in,
              std::vector<uint8_t>* out,
              int zstd_level) {
  switch (compression) {
    case Compression::kNone:
      out->assign(in.begin(), in.end());
      return true;
    case Compression::kZstd:
      return CompressZstd(in, out, zstd_level);
    case Compression::kLz4Frame:
      return CompressLz4Frame(in, out);
    case Compression::kBz2:
      return CompressBz2(in, out);
  }
  return false;
}

}  // namespace swlio::drivers::bag
