/// libFuzzer: MRPT rawlogs (plain or gzip) through the whole reader, every scan converted.
#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "io/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace revisit;
    const auto file = fuzz::WriteInput(fuzz::Scratch() / "input.rawlog", data, size);
    try {
        auto reader = OpenDataset(file);
        while (reader->Next()) {
        }
    } catch (const DatasetError&) {
    }
    return 0;
}
