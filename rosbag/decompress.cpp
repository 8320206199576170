#include "rosbag/decompress.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <memory>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

void CheckSize(std::size_t size, const std::string& context) {
  if (size > kMaxChunkBytes) {
    throw Error(context + ": announces " + std::to_string(size) +
                " bytes uncompressed, more than the limit of " + std::to_string(kMaxChunkBytes) +
                " (corrupt size field?)");
  }
}

std::string SizeMismatch(const std::string& context, const char* codec, std::size_t got,
                         std::size_t size) {
  return context + ": " + codec + " data decompresses to " + std::to_string(got) +
         " bytes, the container announces " + std::to_string(size);
}

}  // namespace

std::string DecompressBz2(std::string_view data, std::size_t size, const std::string& context) {
  CheckSize(size, context);
  std::string out(size, '\0');
  // One byte more than announced, so that longer output is detected rather than cut.
  out.resize(size + 1);
  unsigned int out_size = static_cast<unsigned int>(out.size());
  const int rc = BZ2_bzBuffToBuffDecompress(out.data(), &out_size, const_cast<char*>(data.data()),
                                            static_cast<unsigned int>(data.size()), 0, 0);
  if (rc == BZ_OUTBUFF_FULL) throw Error(context + ": bz2 data is longer than announced");
  if (rc != BZ_OK) {
    throw Error(context + ": corrupt bz2 data (libbz2 error " + std::to_string(rc) + ")");
  }
  if (out_size != size) throw Error(SizeMismatch(context, "bz2", out_size, size));
  out.resize(size);
  return out;
}

std::string DecompressLz4Frame(std::string_view data, std::size_t size,
                               const std::string& context) {
  CheckSize(size, context);
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    throw Error(context + ": cannot create an lz4 decompression context");
  }
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> dctx(
      raw, &LZ4F_freeDecompressionContext);
  std::string out(size, '\0');
  std::size_t in_pos = 0, out_pos = 0;
  std::size_t hint = 1;
  while (in_pos < data.size() && hint != 0) {
    std::size_t out_avail = out.size() - out_pos, in_avail = data.size() - in_pos;
    char overflow;  // a frame with more output than announced writes here and is refused
    char* dst = out_avail > 0 ? out.data() + out_pos : &overflow;
    if (out_avail == 0) out_avail = 1;
    hint = LZ4F_decompress(dctx.get(), dst, &out_avail, data.data() + in_pos, &in_avail, nullptr);
    if (LZ4F_isError(hint)) {
      throw Error(context + ": corrupt lz4 data (" + LZ4F_getErrorName(hint) + ")");
    }
    if (dst == &overflow && out_avail > 0) {
      throw Error(context + ": lz4 data is longer than announced");
    }
    in_pos += in_avail;
    out_pos += dst == &overflow ? 0 : out_avail;
    if (in_avail == 0 && out_avail == 0) break;  // no progress: the input is cut
  }
  if (hint != 0) throw Error(context + ": lz4 data ends inside its frame (truncated)");
  if (out_pos != size) throw Error(SizeMismatch(context, "lz4", out_pos, size));
  return out;
}

std::string DecompressZstd(std::string_view data, std::size_t size, const std::string& context) {
  CheckSize(size, context);
  std::string out(size, '\0');
  const std::size_t got = ZSTD_decompress(out.data(), out.size(), data.data(), data.size());
  if (ZSTD_isError(got)) {
    throw Error(context + ": corrupt zstd data (" + ZSTD_getErrorName(got) + ")");
  }
  if (got != size) throw Error(SizeMismatch(context, "zstd", got, size));
  return out;
}

std::string DecompressZstdFrame(std::string_view data, const std::string& context) {
  const unsigned long long announced = ZSTD_getFrameContentSize(data.data(), data.size());
  if (announced == ZSTD_CONTENTSIZE_ERROR) throw Error(context + ": not zstd data");
  if (announced != ZSTD_CONTENTSIZE_UNKNOWN) {
    return DecompressZstd(data, static_cast<std::size_t>(announced), context);
  }
  // A streamed frame (no size in its header): decompress in steps, up to kMaxChunkBytes.
  const std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> dctx(ZSTD_createDCtx(),
                                                                  &ZSTD_freeDCtx);
  std::string out;
  ZSTD_inBuffer in{data.data(), data.size(), 0};
  std::size_t rc = 1;
  while (rc != 0) {
    if (out.size() >= kMaxChunkBytes) {
      throw Error(context + ": zstd data decompresses to more than " +
                  std::to_string(kMaxChunkBytes) + " bytes");
    }
    const std::size_t at = out.size();
    out.resize(at + (std::size_t{1} << 16));
    ZSTD_outBuffer o{out.data() + at, out.size() - at, 0};
    const std::size_t before = in.pos;
    rc = ZSTD_decompressStream(dctx.get(), &o, &in);
    if (ZSTD_isError(rc)) {
      throw Error(context + ": corrupt zstd data (" + ZSTD_getErrorName(rc) + ")");
    }
    out.resize(at + o.pos);
    if (rc != 0 && in.pos == before && o.pos == 0) {
      throw Error(context + ": zstd data ends inside its frame (truncated)");
    }
  }
  return out;
}

}  // namespace fleetmerge
