/// libFuzzer target for every reader: the first byte picks the format, the rest is the file.
/// Build and run with `make fuzz` (clang, -fsanitize=fuzzer,address,undefined). Any outcome but a
/// clean read or a DatasetError (a crash, a sanitizer report, another exception) is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "io/cloud_files.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"

namespace {

std::filesystem::path WriteInput(const char* extension, const std::uint8_t* data, std::size_t size) {
    const auto file = std::filesystem::temp_directory_path() / ("revisit-fuzz-" + std::to_string(getpid()) + extension);
    std::FILE* f = std::fopen(file.c_str(), "wb");
    if (f) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    return file;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    static const char* const kExtensions[] = {".bin", ".pcd", ".ply", ".rawlog", ".txt"};
    // REVISIT_FUZZ_NO_RAWLOG=1 leaves MRPT's deserializer out, whose allocations on corrupt sizes
    // (a known MRPT limitation) otherwise dominate the findings.
    static const bool skip_rawlog = std::getenv("REVISIT_FUZZ_NO_RAWLOG") != nullptr;
    int format = data[0] % 5;
    if (skip_rawlog && format == 3) format = 4;
    const auto file = WriteInput(kExtensions[format], data + 1, size - 1);
    try {
        switch (format) {
            case 0: revisit::LoadKittiBin(file); break;
            case 1: revisit::LoadPcd(file); break;
            case 2: revisit::LoadPly(file); break;
            case 3: {
                auto reader = revisit::OpenDataset(file);
                while (reader->Next()) {
                }
                break;
            }
            default: revisit::ReadPoses(file); break;
        }
    } catch (const revisit::DatasetError&) {
        // the expected outcome for bad input
    }
    std::filesystem::remove(file);
    return 0;
}
