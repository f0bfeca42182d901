#pragma once
/// Shared by the libFuzzer targets: the input becomes a file (the readers take paths), and the only
/// acceptable outcomes are a clean read or a DatasetError/ConfigError. Anything else (another
/// exception, a crash, a sanitizer report, a hang past -timeout, memory past -rss_limit_mb) is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

namespace revisit::fuzz {

/// A per-process scratch folder under the temporary directory.
inline const std::filesystem::path& Scratch() {
    static const std::filesystem::path dir = [] {
        auto path = std::filesystem::temp_directory_path() / ("revisit-fuzz-" + std::to_string(getpid()));
        std::filesystem::create_directories(path);
        return path;
    }();
    return dir;
}

inline std::filesystem::path WriteInput(const std::filesystem::path& file, const std::uint8_t* data, std::size_t size) {
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if (f) {
        if (size > 0) std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    return file;
}

}  // namespace revisit::fuzz
