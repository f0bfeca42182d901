/// libFuzzer: MCAP files through the whole ROS bag reader, strict and with allow_truncated.
#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "io/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace revisit;
    const auto file = fuzz::WriteInput(fuzz::Scratch() / "input.mcap", data, size);
    for (const bool allow_truncated : {false, true}) {
        ReaderOptions options;
        options.allow_truncated = allow_truncated;
        try {
            auto reader = OpenDataset(file, options);
            while (reader->Next()) {
            }
        } catch (const DatasetError&) {
        }
    }
    return 0;
}
