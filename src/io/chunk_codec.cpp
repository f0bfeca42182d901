#include "io/chunk_codec.hpp"

#include <bzlib.h>
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <limits>
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

/// bzip2 (ROS 1 bags' bz2 chunks): one stream, as rosbag writes it.
std::size_t Bz2(const std::uint8_t* input, std::size_t size, std::size_t declared, bool partial, std::vector<std::uint8_t>& out) {
    bz_stream stream{};
    if (BZ2_bzDecompressInit(&stream, 0, 0) != BZ_OK) throw WireError("bz2: no decompression context");
    const std::unique_ptr<bz_stream, decltype(&BZ2_bzDecompressEnd)> end(&stream, &BZ2_bzDecompressEnd);
    std::size_t produced = 0;
    stream.next_in = const_cast<char*>(reinterpret_cast<const char*>(input));
    stream.avail_in = unsigned(std::min<std::size_t>(size, std::numeric_limits<unsigned>::max()));
    while (true) {
        Reserve(out, produced, declared);
        const std::size_t room = std::min(out.size(), declared) - produced;
        stream.next_out = reinterpret_cast<char*>(out.data() + produced);
        stream.avail_out = unsigned(std::min<std::size_t>(room, std::numeric_limits<unsigned>::max()));
        const unsigned before_in = stream.avail_in, before_out = stream.avail_out;
        const int status = BZ2_bzDecompress(&stream);
        produced += before_out - stream.avail_out;
        if (status == BZ_STREAM_END) break;
        if (status != BZ_OK) {
            if (partial) return produced;
            throw WireError("bz2: damaged data (bzip2 status " + std::to_string(status) + ")");
        }
        if (stream.avail_in == before_in && stream.avail_out == before_out) {
            if (partial) break;
            throw WireError(produced == declared ? "bz2 data decompresses to more than the declared " + std::to_string(declared) + " bytes"
                                                 : "bz2 stream ends early: " + std::to_string(produced) + " of " +
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
    } else if (compression == "bz2") {
        produced = Bz2(input, size, declared, partial, out);
    } else {
        throw WireError("compression '" + compression + "' is not supported (zstd, lz4, bz2 or none)");
    }
    if (!partial && produced != declared) {
        throw WireError(compression + " data decompresses to " + std::to_string(produced) + " bytes, the chunk declares " +
                        std::to_string(declared));
    }
    return produced;
}

}  // namespace revisit
