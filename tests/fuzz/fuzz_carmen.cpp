/// libFuzzer: CARMEN logs (plain, gzip or bzip2) through the whole reader, every scan converted. The
/// first byte picks the laser read (any, FLASER, RLASER, ROBOTLASER1) and whether the aperture is
/// overridden; the rest is the file.
#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "io/reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    using namespace revisit;
    static const char* const kLabels[] = {"", "FLASER", "RLASER", "ROBOTLASER1"};
    ReaderOptions options;
    options.sensor_label = kLabels[data[0] % 4];
    options.laser_aperture = (data[0] / 4) % 2 == 1 ? 1.0 : 0.0;
    const auto file = fuzz::WriteInput(fuzz::Scratch() / "input.log", data + 1, size - 1);
    try {
        auto reader = OpenDataset(file, options);
        while (reader->Next()) {
        }
    } catch (const DatasetError&) {
    }
    return 0;
}
