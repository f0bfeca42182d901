/// libFuzzer: YAML configuration files through the schema (every key bound, every value checked).
#include "core/error.hpp"
#include "fuzz_support.hpp"
#include "config/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace revisit;
    const auto file = fuzz::WriteInput(fuzz::Scratch() / "config.yaml", data, size);
    try {
        LoadConfig({file.string()}, {});
    } catch (const ConfigError&) {
    }
    return 0;
}
