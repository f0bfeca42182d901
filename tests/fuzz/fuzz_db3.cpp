/// libFuzzer: rosbag2 sqlite3 folders (the input is the .db3 file) through the whole ROS bag reader.
#include <fstream>

#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "io/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace revisit;
    static const auto folder = [] {
        const auto path = fuzz::Scratch() / "bag";
        std::filesystem::create_directories(path);
        std::ofstream(path / "metadata.yaml") << "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n";
        return path;
    }();
    fuzz::WriteInput(folder / "bag_0.db3", data, size);
    try {
        auto reader = OpenDataset(folder);
        while (reader->Next()) {
        }
    } catch (const DatasetError&) {
    }
    return 0;
}
