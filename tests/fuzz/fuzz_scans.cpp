/// libFuzzer: the scan readers. The first byte picks the format (KITTI .bin, PCD, PLY), the rest is the file.
#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "io/cloud_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    using namespace revisit;
    static const char* const kNames[] = {"scan.bin", "scan.pcd", "scan.ply"};
    const int format = data[0] % 3;
    const auto file = fuzz::WriteInput(fuzz::Scratch() / kNames[format], data + 1, size - 1);
    try {
        if (format == 0) LoadKittiBin(file);
        else if (format == 1) LoadPcd(file);
        else LoadPly(file);
    } catch (const DatasetError&) {
    }
    return 0;
}
