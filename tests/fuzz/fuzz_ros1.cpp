/// libFuzzer: ROS 1 bags through rosbag_storage and the ROS bag reader.
#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "io/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace revisit;
    const auto file = fuzz::WriteInput(fuzz::Scratch() / "input.bag", data, size);
    try {
        auto reader = OpenDataset(file);
        while (reader->Next()) {
        }
    } catch (const DatasetError&) {
    }
    return 0;
}
