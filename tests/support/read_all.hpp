#pragma once
/// Every scan of a dataset, in order (tests read small datasets whole).
#include <filesystem>
#include <vector>

#include "io/reader.hpp"

namespace revisit::test {

inline std::vector<Scan> ReadAllScans(const std::filesystem::path& path, const ReaderOptions& options = {}) {
    auto reader = OpenDataset(path, options);
    std::vector<Scan> scans;
    while (auto scan = reader->Next()) scans.push_back(std::move(*scan));
    return scans;
}

}  // namespace revisit::test
