// Chunk decompression through libzstd, liblz4 (frame API) and libbz2; see decompress.h.

#include "swlio/drivers/bag/decompress.h"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <climits>
#include <memory>

namespace swlio::drivers::bag {
namespace {

bool DecompressZstd(std::span<const uint8_t> in, std::vector<uint8_t>* out, std::string* error) {
  const unsigned long long declared = ZSTD_getFrameContentSize(in.data(), in.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR) {
    *error = "zstd: not a zstd frame";
    return false;
  }
  if (declared != ZSTD_CONTENTSIZE_UNKNOWN && declared != out->size()) {
    *error = "zstd: frame declares " + std::to_string(declared) + " bytes, container " +
             std::to_string(out->size());
    return false;
  }
  const size_t n = ZSTD_decompress(out->data(), out->size(), in.data(), in.size());
  if (ZSTD_isError(n)) {
    *error = std::string("zstd: ") + ZSTD_getErrorName(n);
    return false;
  }
  if (n != out->size()) {
    *error =
        "zstd: " + std::to_string(n) + " bytes, container states " + std::to_string(out->size());
    return false;
  }
  return true;
}

struct Lz4ContextFree {
  void operator()(LZ4F_dctx* c) const { LZ4F_freeDecompressionContext(c); }
};

bool DecompressLz4Frame(std::span<const uint8_t> in,
                        std::vector<uint8_t>* out,
                        std::string* error) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    *error = "lz4: cannot create a decompression context";
    return false;
  }
  const std::unique_ptr<LZ4F_dctx, Lz4ContextFree> ctx(raw);
  size_t in_pos = 0;
  size_t out_pos = 0;
  uint8_t scratch = 0;  // detects output beyond the stated size
  for (;;) {
    const bool full = out_pos == out->size();
    uint8_t* dst = full ? &scratch : out->data() + out_pos;
    size_t dst_size = full ? 1 : out->size() - out_pos;
    size_t src_size = in.size() - in_pos;
    const size_t hint =
        LZ4F_decompress(ctx.get(), dst, &dst_size, in.data() + in_pos, &src_size, nullptr);
    if (LZ4F_isError(hint)) {
      *error = std::string("lz4: ") + LZ4F_getErrorName(hint);
      return false;
    }
    if (full && dst_size > 0) {
      *error = "lz4: more than the stated " + std::to_string(out->size()) + " bytes";
      return false;
    }
    in_pos += src_size;
    out_pos += full ? 0 : dst_size;
    if (hint == 0 && in_pos == in.size()) break;
    if (src_size == 0 && dst_size == 0) {
      *error = "lz4: the stream ends inside a frame";
      return false;
    }
  }
  if (out_pos != out->size()) {
    *error = "lz4: " + std::to_string(out_pos) + " bytes, container states " +
             std::to_string(out->size());
    return false;
  }
  return true;
}

bool DecompressBz2(std::span<const uint8_t> in, std::vector<uint8_t>* out, std::string* error) {
  if (in.size() > UINT_MAX || out->size() > UINT_MAX) {
    *error = "bz2: larger than 4 GiB";
    return false;
  }
  auto dest_len = static_cast<unsigned int>(out->size());
  // libbz2 takes a non-const source pointer but only reads it.
  char* source = const_cast<char*>(reinterpret_cast<const char*>(in.data()));  // NOLINT
  const int rc = BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out->data()), &dest_len, source,
                                            static_cast<unsigned int>(in.size()), 0, 0);
  if (rc == BZ_OUTBUFF_FULL) {
    *error = "bz2: more than the stated " + std::to_string(out->size()) + " bytes";
    return false;
  }
  if (rc != BZ_OK) {
    *error = "bz2: damaged stream (libbz2 error " + std::to_string(rc) + ")";
    return false;
  }
  if (dest_len != out->size()) {
    *error = "bz2: " + std::to_string(dest_len) + " bytes, container states " +
             std::to_string(out->size());
    return false;
  }
  return true;
}

}  // namespace

bool ParseCompression(std::string_view name, Compression* out) {
  if (name.empty() || name == "none") {
    *out = Compression::kNone;
  } else if (name == "zstd") {
    *out = Compression::kZstd;
  } else if (name == "lz4") {
    *out = Compression::kLz4Frame;
  } else if (name == "bz2") {
    *out = Compression::kBz2;
  } else {
    return false;
  }
  return true;
}

bool Decompress(Compression compression,
                std::span<const uint8_t> in,
                uint64_t expected_size,
                std::vector<uint8_t>* out,
                std::string* error) {
  out->resize(static_cast<size_t>(expected_size));
  switch (compression) {
    case Compression::kNone:
      if (in.size() != expected_size) {
        *error = "uncompressed size " + std::to_string(in.size()) + " differs from the stated " +
                 std::to_string(expected_size);
        return false;
      }
      out->assign(in.begin(), in.end());
      return true;
    case Compression::kZstd:
      return DecompressZstd(in, out, error);
    case Compression::kLz4Frame:
      return DecompressLz4Frame(in, out, error);
    case Compression::kBz2:
      return DecompressBz2(in, out, error);
  }
  *error = "unknown compression";
  return false;
}

}  // namespace swlio::drivers::bag
