#include "io/chunk_codec.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <memory>

#include "io/ros_wire.hpp"

namespace revisit {
namespace {

constexpr std::size_t kGrowStep = 4u << 20;  ///< [bytes] output grows by at most this beyond what was produced

/// Room for more output: the buffer keeps its size across chunks, so it is zeroed once.
void Reserve(std::vector<std::uint8_t>& out, std::size_t produced, std::size_t declared) {
    const std::size_t want = std::min(declared, produced + std::max(kGrowStep, produced));
    if (out.size() < want) out.resize(want);
}

std::size_t Zstd(const std::uint8_t* input, std::size_t size, std::size_t declared, bool partial,
                 std::vector<std::uint8_t>& out) {
    static thread_local std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(), &ZSTD_freeDCtx);
    ZSTD_DCtx_reset(context.get(), ZSTD_reset_session_only);
    ZSTD_inBuffer in{input, size, 0};
    std::size_t produced = 0;
    while (true) {
        Reserve(out, produced, declared);
        ZSTD_outBuffer o{out.data(), std::min(out.size(), declared), produced};
        const std::size_t consumed = in.pos;
        const std::size_t status = ZSTD_decompressStream(context.get(), &o, &in);
        if (ZSTD_isError(status)) {
            if (partial) return produced;
            throw WireError(std::string("zstd: ") + ZSTD_getErrorName(status));
        }
        const bool progressed = o.pos > produced || in.pos > consumed;
        produced = o.pos;
        if (status == 0 && in.pos == in.size) break;  // the frame(s) complete, the input used up
        if (!progressed) {
            if (partial) break;
            throw WireError(produced == declared ? "zstd data decompresses to more than the declared " + std::to_string(declared) + " bytes"
                                                 : "zstd frame ends early: " + std::to_string(produced) + " of " +
                                                       std::to_string(declared) + " bytes");
        }
    }
    return produced;
}

std::size_t Lz4(const std::uint8_t* input, std::size_t size, std::size_t declared, bool partial,
                std::vector<std::uint8_t>& out) {
    LZ4F_dctx* raw = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw WireError("lz4: no decompression context");
    const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(raw, &LZ4F_freeDecompressionContext);
    std::size_t consumed = 0, produced = 0, hint = 1;
    while (consumed < size || hint != 0) {
        Reserve(out, produced, declared);
        std::size_t out_size = std::min(out.size(), declared) - produced;
        std::size_t in_size = size - consumed;
        hint = LZ4F_decompress(context.get(), out.data() + produced, &out_size, input + consumed, &in_size, nullptr);
        if (LZ4F_isError(hint)) {
            if (partial) return produced;
            throw WireError(std::string("lz4: ") + LZ4F_getErrorName(hint));
        }
        consumed += in_size;
        produced += out_size;
        if (hint == 0 && consumed == size) break;
        if (in_size == 0 && out_size == 0) {
            if (partial) break;
            throw WireError(produced == declared ? "lz4 data decompresses to more than the declared " + std::to_string(declared) + " bytes"
                                                 : "lz4 frame ends early: " + std::to_string(produced) + " of " +
                                                       std::to_string(declared) + " bytes");
        }
    }
    return produced;
}

}  // namespace

std::size_t Decompress(const std::string& compression, const std::uint8_t* input, std::size_t size,
                       std::size_t declared, bool partial, std::vector<std::uint8_t>& out) {
    std::size_t produced = 0;
    if (compression == "zstd") {
        produced = Zstd(input, size, declared, partial, out);
    } else if (compression == "lz4") {
        produced = Lz4(input, size, declared, partial, out);
    } else {
        throw WireError("compression '" + compression + "' is not supported (zstd, lz4 or none)");
    }
    if (!partial && produced != declared) {
        throw WireError(compression + " data decompresses to " + std::to_string(produced) + " bytes, the chunk declares " +
                        std::to_string(declared));
    }
    return produced;
}

}  // namespace revisit
