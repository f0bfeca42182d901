/// libFuzzer: the closure database (database.bin) under the default configuration.
#include "closures/database_io.hpp"
#include "core/error.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace revisit;
    const auto file = fuzz::WriteInput(fuzz::Scratch() / "database.bin", data, size);
    try {
        const ClosureDetector detector = LoadDatabase(file, ClosureDetectorConfig{});
        for (std::size_t i = 0; i < detector.maps().size(); ++i) detector.Image(i);  // PNG decoding too
    } catch (const DatasetError&) {
    }
    return 0;
}
