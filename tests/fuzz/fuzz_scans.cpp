/// libFuzzer: the scan readers. The first byte picks the format (KITTI .bin, PCD, PLY, NCLT .bin, the
/// four HeLiPR .bin layouts), the rest is the file.
#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "io/cloud_files.hpp"
#include "io/helipr.hpp"
#include "io/nclt.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    using namespace revisit;
    static const char* const kNames[] = {"scan.bin", "scan.pcd", "scan.ply", "nclt.bin"};
    static const char* const kHeLiPR[] = {"Ouster", "Velodyne", "Avia", "Aeva"};
    const int format = data[0] % 8;
    const auto file = fuzz::WriteInput(fuzz::Scratch() / (format < 4 ? kNames[format] : "helipr.bin"), data + 1, size - 1);
    try {
        if (format == 0) LoadKittiBin(file);
        else if (format == 1) LoadPcd(file);
        else if (format == 2) LoadPly(file);
        else if (format == 3) LoadNcltBin(file);
        else LoadHeLiPRBin(file, kHeLiPR[format - 4]);
    } catch (const DatasetError&) {
    }
    return 0;
}
