/// libFuzzer: trajectories (KITTI or TUM), times.txt and calib.txt. The first byte picks the reader.
#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "io/folder_reader.hpp"
#include "io/trajectory_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    using namespace revisit;
    const int reader = data[0] % 3;
    const auto file = fuzz::WriteInput(fuzz::Scratch() / "input.txt", data + 1, size - 1);
    try {
        if (reader == 0) ReadPoses(file);
        else if (reader == 1) ReadTimes(file);
        else ReadKittiTr(file);
    } catch (const DatasetError&) {
    }
    return 0;
}
