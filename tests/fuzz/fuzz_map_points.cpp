/// libFuzzer: a local map's points as the run folder keeps them (maps/map_NNNN.rvmap). Each input is
/// read as it is and once more resealed (its size field and CRC-32 made to match), so that mutations
/// reach the parser behind the checksum.
#include <zlib.h>

#include <cstring>
#include <string>
#include <string_view>

#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "runfolder/map_points_file.hpp"

namespace {

constexpr std::size_t kSizeField = 28;   // magic, version, count, step, cells
constexpr std::size_t kHeaderBytes = 36;
constexpr std::size_t kTrailerBytes = 4;

void Decode(std::string_view bytes) {
    try {
        for (const auto& p : revisit::DecodeMapPoints(bytes, "map_0000.rvmap"))
            if (!p.allFinite()) __builtin_trap();  // a file that reads holds finite points
    } catch (const revisit::DatasetError&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    Decode(bytes);
    if (bytes.size() < kHeaderBytes + kTrailerBytes) return 0;
    const std::uint64_t compressed = bytes.size() - kHeaderBytes - kTrailerBytes;
    std::memcpy(bytes.data() + kSizeField, &compressed, sizeof(compressed));
    const auto crc = static_cast<std::uint32_t>(
        crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size() - kTrailerBytes)));
    std::memcpy(bytes.data() + bytes.size() - kTrailerBytes, &crc, sizeof(crc));
    Decode(bytes);
    return 0;
}
