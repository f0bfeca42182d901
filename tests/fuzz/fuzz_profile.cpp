/// libFuzzer: the settings-from-the-data profile (and the ground fit inside it) on scans of any
/// coordinates: the input's bytes are float x y z triples, split into up to three scans. Its memory
/// must stay bounded by the number of points whatever the values (far points once made the ground
/// grid gigabytes); run with -rss_limit_mb to catch a regression.
#include <cstdint>
#include <cstring>

#include "closures/ground_alignment.hpp"
#include "settings/data_profile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace revisit;
    const std::size_t points = size / (3 * sizeof(float));
    DataProfiler profiler(3);
    for (std::size_t s = 0; s < 3; ++s) {
        Scan scan;
        scan.index = s;
        scan.timestamp = 0.1 * static_cast<double>(s);
        for (std::size_t i = s * points / 3; i < (s + 1) * points / 3; ++i) {
            float xyz[3];
            std::memcpy(xyz, data + i * sizeof(xyz), sizeof(xyz));
            scan.points.emplace_back(xyz[0], xyz[1], xyz[2]);
        }
        AlignGround(scan.points);
        profiler.Add(scan);
    }
    const DataProfile profile = profiler.Profile();
    (void)profile.Describe();
    return 0;
}
