#include "runfolder/map_points_file.hpp"

#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"

namespace revisit {
namespace {

constexpr char kMagic[4] = {'R', 'V', 'M', 'P'};
constexpr std::uint32_t kVersion = 1;
/// magic, version, point count, step, cells per block, compressed size
constexpr std::size_t kHeaderBytes = 4 + 4 + 8 + 8 + 4 + 8;
constexpr std::size_t kTrailerBytes = 4;  // CRC-32 of everything before it
/// Per point: three int32 block deltas and three uint8 cells.
constexpr std::size_t kPayloadBytesPerPoint = 3 * 4 + 3;
/// Level 9: a highway map 3-4% smaller than at the default 3; writing a map took 420 ms instead of
/// the KITTI .bin's 245 ms on a loaded machine (docs/performance.md, "Long drives").
constexpr int kZstdLevel = 9;

/// A point on the grid: the 50-cell block it lies in and its cell within, per axis.
struct GridPoint {
    std::array<std::int32_t, 3> block;
    std::array<std::uint8_t, 3> cell;
    bool operator<(const GridPoint& other) const {
        return block != other.block ? block < other.block : cell < other.cell;
    }
};

/// Grid indices stay below this in magnitude: blocks are int32 and their deltas must stay int32 too.
constexpr double kGridLimit = double(kMapPointCellsPerVoxel) * double(1 << 29);

std::vector<GridPoint> ToGrid(const std::vector<Eigen::Vector3f>& points, double step_m) {
    if (!(step_m > 0.0)) throw std::invalid_argument("map points: the grid step must be positive");
    const double limit = kGridLimit;
    std::vector<GridPoint> grid(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            const double index = std::round(double(points[i][axis]) / step_m);
            if (!(std::abs(index) < limit)) {
                throw std::invalid_argument("map points: point " + std::to_string(i) + " is not finite or too far from its map's origin");
            }
            const auto q = static_cast<std::int64_t>(index);
            const std::int64_t block = q >= 0 ? q / kMapPointCellsPerVoxel : -((-q + kMapPointCellsPerVoxel - 1) / kMapPointCellsPerVoxel);
            grid[i].block[std::size_t(axis)] = static_cast<std::int32_t>(block);
            grid[i].cell[std::size_t(axis)] = static_cast<std::uint8_t>(q - block * kMapPointCellsPerVoxel);
        }
    }
    // A canonical order, and neighbours in it are neighbours in space: the block deltas are small.
    std::sort(grid.begin(), grid.end());
    return grid;
}

/// The one place grid coordinates become floats: writer and reader agree to the bit.
float Coordinate(std::int32_t block, std::uint8_t cell, double step_m) {
    return static_cast<float>(double(std::int64_t(block) * kMapPointCellsPerVoxel + cell) * step_m);
}

std::vector<Eigen::Vector3f> FromGrid(const std::vector<GridPoint>& grid, double step_m) {
    std::vector<Eigen::Vector3f> points(grid.size());
    for (std::size_t i = 0; i < grid.size(); ++i) {
        for (int axis = 0; axis < 3; ++axis) {
            points[i][axis] = Coordinate(grid[i].block[std::size_t(axis)], grid[i].cell[std::size_t(axis)], step_m);
        }
    }
    return points;
}

template <typename T>
void Append(std::string& out, T value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <typename T>
T Take(const char*& at) {
    T value;
    std::memcpy(&value, at, sizeof(T));
    at += sizeof(T);
    return value;
}

std::uint32_t Crc32(std::string_view bytes) {
    uLong crc = crc32(0L, Z_NULL, 0);
    // zlib takes uInt lengths: feed in pieces.
    for (std::size_t at = 0; at < bytes.size(); at += 1u << 30) {
        const std::size_t n = std::min<std::size_t>(bytes.size() - at, 1u << 30);
        crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), static_cast<uInt>(n));
    }
    return static_cast<std::uint32_t>(crc);
}

/// Three planes of block deltas, each byte-shuffled (every point's byte 0, then byte 1, ...: the high
/// bytes are nearly all 0 or 0xff and compress away), then three planes of cells.
std::string Payload(const std::vector<GridPoint>& grid) {
    const std::size_t n = grid.size();
    std::string payload(n * kPayloadBytesPerPoint, '\0');
    for (std::size_t axis = 0; axis < 3; ++axis) {
        std::int32_t previous = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const auto delta = static_cast<std::uint32_t>(grid[i].block[axis]) - static_cast<std::uint32_t>(previous);
            previous = grid[i].block[axis];
            for (std::size_t byte = 0; byte < 4; ++byte) payload[(axis * 4 + byte) * n + i] = static_cast<char>((delta >> (8 * byte)) & 0xffu);
        }
    }
    for (std::size_t axis = 0; axis < 3; ++axis) {
        for (std::size_t i = 0; i < n; ++i) payload[(12 + axis) * n + i] = static_cast<char>(grid[i].cell[axis]);
    }
    return payload;
}

}  // namespace

std::vector<Eigen::Vector3f> SnapToMapPointGrid(const std::vector<Eigen::Vector3f>& points, double step_m) {
    return FromGrid(ToGrid(points, step_m), step_m);
}

std::string EncodeMapPoints(const std::vector<Eigen::Vector3f>& points, double step_m) {
    const std::string payload = Payload(ToGrid(points, step_m));
    std::string compressed(ZSTD_compressBound(payload.size()), '\0');
    std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> context(ZSTD_createCCtx(), &ZSTD_freeCCtx);
    ZSTD_CCtx_setParameter(context.get(), ZSTD_c_compressionLevel, kZstdLevel);
    ZSTD_CCtx_setParameter(context.get(), ZSTD_c_checksumFlag, 1);
    const std::size_t size = ZSTD_compress2(context.get(), compressed.data(), compressed.size(), payload.data(), payload.size());
    if (ZSTD_isError(size)) throw std::runtime_error(std::string("map points: zstd: ") + ZSTD_getErrorName(size));
    compressed.resize(size);

    std::string out;
    out.reserve(kHeaderBytes + size + kTrailerBytes);
    out.append(kMagic, sizeof(kMagic));
    Append(out, kVersion);
    Append(out, std::uint64_t(points.size()));
    Append(out, step_m);
    Append(out, std::uint32_t(kMapPointCellsPerVoxel));
    Append(out, std::uint64_t(size));
    out += compressed;
    Append(out, Crc32(out));
    return out;
}

std::vector<Eigen::Vector3f> DecodeMapPoints(std::string_view bytes, const std::filesystem::path& file) {
    const auto fail = [&file](const std::string& problem) { return DatasetError(file, "damaged map points file: " + problem); };
    if (bytes.size() < 4 || std::memcmp(bytes.data(), kMagic, 4) != 0) throw DatasetError(file, "not a revisit map points file (bad magic)");
    if (bytes.size() < kHeaderBytes + kTrailerBytes) throw fail("truncated (" + std::to_string(bytes.size()) + " bytes, shorter than a header)");
    const char* at = bytes.data() + 4;
    const auto version = Take<std::uint32_t>(at);
    if (version != kVersion) {
        throw DatasetError(file, "map points file version " + std::to_string(version) + ", this build reads version " + std::to_string(kVersion));
    }
    const auto count = Take<std::uint64_t>(at);
    const auto step_m = Take<double>(at);
    const auto cells = Take<std::uint32_t>(at);
    const auto compressed_size = Take<std::uint64_t>(at);
    if (compressed_size != bytes.size() - kHeaderBytes - kTrailerBytes) {
        throw fail("truncated or padded (" + std::to_string(bytes.size()) + " bytes; the header says " +
                   std::to_string(compressed_size + kHeaderBytes + kTrailerBytes) + ")");
    }
    std::uint32_t stored_crc;
    std::memcpy(&stored_crc, bytes.data() + bytes.size() - kTrailerBytes, kTrailerBytes);
    if (stored_crc != Crc32(bytes.substr(0, bytes.size() - kTrailerBytes))) throw fail("checksum mismatch");
    // The largest step a run writes: the largest `output.map_voxel` (100 m) over the cells per voxel. A
    // larger one would put sealed points beyond any float.
    constexpr double kMaxStep = 100.0 / kMapPointCellsPerVoxel;
    if (!(step_m > 0.0) || !(step_m <= kMaxStep) || cells != std::uint32_t(kMapPointCellsPerVoxel)) throw fail("grid step or cells out of range");
    // A count the compressed bytes cannot plausibly hold is refused before anything is allocated.
    const std::uint64_t payload_size = count * kPayloadBytesPerPoint;
    if (count > (std::uint64_t(1) << 40) || payload_size > 256 * compressed_size + (std::uint64_t(16) << 20)) {
        throw fail("the point count " + std::to_string(count) + " does not fit " + std::to_string(compressed_size) + " compressed bytes");
    }
    const char* compressed = bytes.data() + kHeaderBytes;
    if (ZSTD_getFrameContentSize(compressed, compressed_size) != payload_size) throw fail("the compressed frame's size does not match the point count");
    std::string payload(payload_size, '\0');
    const std::size_t produced = ZSTD_decompress(payload.data(), payload.size(), compressed, compressed_size);
    if (ZSTD_isError(produced)) throw fail(std::string("zstd: ") + ZSTD_getErrorName(produced));
    if (produced != payload_size) throw fail("the compressed frame holds fewer points than its header says");

    const std::size_t n = count;
    std::vector<GridPoint> grid(n);
    for (std::size_t axis = 0; axis < 3; ++axis) {
        std::uint32_t block = 0;
        for (std::size_t i = 0; i < n; ++i) {
            std::uint32_t delta = 0;
            for (std::size_t byte = 0; byte < 4; ++byte) delta |= std::uint32_t(std::uint8_t(payload[(axis * 4 + byte) * n + i])) << (8 * byte);
            block += delta;
            grid[i].block[axis] = static_cast<std::int32_t>(block);
            const auto cell = static_cast<std::uint8_t>(payload[(12 + axis) * n + i]);
            if (cell >= kMapPointCellsPerVoxel) throw fail("cell out of range at point " + std::to_string(i));
            grid[i].cell[axis] = cell;
            // The writer's range (ToGrid): a point beyond it was never written.
            const double index = double(grid[i].block[axis]) * kMapPointCellsPerVoxel + cell;
            if (!(std::abs(index) < kGridLimit)) throw fail("point " + std::to_string(i) + " lies beyond the grid's range");
        }
    }
    return FromGrid(grid, step_m);
}

void SaveMapPoints(const std::filesystem::path& file, const std::vector<Eigen::Vector3f>& points, double step_m) {
    WriteFileAtomically(file, EncodeMapPoints(points, step_m));
}

std::vector<Eigen::Vector3f> LoadMapPoints(const std::filesystem::path& file) {
    std::ifstream in = OpenForReading(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw DatasetError(file, "cannot read");
    return DecodeMapPoints(bytes, file);
}

}  // namespace revisit
