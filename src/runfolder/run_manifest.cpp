#include "runfolder/run_manifest.hpp"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <system_error>

#include "core/error.hpp"
#include "core/input_file.hpp"

namespace revisit {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// Result files at the top of a run folder, besides run.json (see ListRunFiles).
const char* const kTopLevelFiles[] = {"config.yaml", "run_options.json", "poses_odometry_kitti.txt", "poses_odometry_tum.txt",
                                      "poses_corrected_kitti.txt", "poses_corrected_tum.txt", "poses_reference_tum.txt",
                                      "closures.csv", "local_maps.csv", "comparisons.csv", "timings.json", "database.bin",
                                      "map_corrected.ply"};

std::string Hex(std::uint32_t value) {
    char text[9];
    std::snprintf(text, sizeof(text), "%08x", static_cast<unsigned>(value));
    return text;
}

void AddFolder(const RunFolder& run, const char* folder, const std::vector<std::string>& extensions, std::vector<ManifestEntry>& out) {
    std::error_code ec;
    const fs::path dir = run.root() / folder;
    if (!fs::is_directory(fs::symlink_status(dir, ec))) return;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (!fs::is_regular_file(entry.symlink_status())) continue;
        const std::string ext = entry.path().extension().string();
        if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) continue;
        out.push_back(DescribeFile(entry.path(), std::string(folder) + "/" + entry.path().filename().string()));
    }
}

}  // namespace

ManifestEntry DescribeFile(const fs::path& file, const std::string& name) {
    std::ifstream in = OpenForReading(file, std::ios::binary);
    ManifestEntry entry;
    entry.name = name;
    uLong crc = crc32(0L, Z_NULL, 0);
    std::vector<char> buffer(1 << 16);
    while (in) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        const std::streamsize got = in.gcount();
        if (got <= 0) break;
        crc = crc32(crc, reinterpret_cast<const Bytef*>(buffer.data()), static_cast<uInt>(got));
        entry.size += static_cast<std::uintmax_t>(got);
    }
    if (in.bad()) throw DatasetError(file, "cannot read");
    entry.crc32 = static_cast<std::uint32_t>(crc);
    return entry;
}

std::vector<ManifestEntry> ListRunFiles(const RunFolder& run) {
    std::vector<ManifestEntry> entries;
    std::error_code ec;
    for (const char* name : kTopLevelFiles) {
        const fs::path file = run.root() / name;
        if (fs::is_regular_file(fs::symlink_status(file, ec))) entries.push_back(DescribeFile(file, name));
    }
    AddFolder(run, "closures", {".json"}, entries);
    AddFolder(run, "maps", {".rvmap", ".bin", ".png"}, entries);
    std::sort(entries.begin(), entries.end(), [](const ManifestEntry& a, const ManifestEntry& b) { return a.name < b.name; });
    return entries;
}

json ManifestJson(const std::vector<ManifestEntry>& entries) {
    json files = json::object();
    for (const auto& e : entries) files[e.name] = {{"size", e.size}, {"crc32", Hex(e.crc32)}};
    return files;
}

void CheckRunManifest(const RunFolder& run, const json& info) {
    if (!info.contains("files")) return;
    const json& files = info.at("files");
    if (!files.is_object()) throw DatasetError(run.run_info(), "'files' is not a table of file names");
    for (const auto& [name, expected] : files.items()) {
        const fs::path relative(name);
        // Only names inside the folder: an absolute path or ".." would check (and trust) a file elsewhere.
        if (name.empty() || relative.is_absolute() || std::find(relative.begin(), relative.end(), "..") != relative.end())
            throw DatasetError(run.run_info(), "'files' lists '" + name + "', which is not a name inside the run folder");
        if (!expected.is_object() || !expected.contains("size") || !expected.at("size").is_number_unsigned() ||
            !expected.contains("crc32") || !expected.at("crc32").is_string())
            throw DatasetError(run.run_info(), "'files': the entry of '" + name + "' has no size and crc32");
        const fs::path file = run.root() / relative;
        std::error_code ec;
        if (!fs::exists(fs::symlink_status(file, ec)))
            throw DatasetError(file, "is missing; run.json lists it as a result of the run (removed after the run?)");
        if (fs::is_directory(fs::symlink_status(file, ec)))
            throw DatasetError(file, "is a folder, expected a file; run.json lists it as a result of the run");
        if (!fs::is_regular_file(fs::symlink_status(file, ec)))
            throw DatasetError(file, "is not a regular file; run.json lists it as a result of the run");
        const ManifestEntry actual = DescribeFile(file, name);
        const auto size = expected.at("size").get<std::uintmax_t>();
        const std::string crc = expected.at("crc32").get<std::string>();
        if (actual.size != size) {
            throw DatasetError(file, "has " + std::to_string(actual.size) + " bytes, run.json says " + std::to_string(size) +
                                         ": cut or changed after the run; rerun, or restore the file");
        }
        if (Hex(actual.crc32) != crc) {
            throw DatasetError(file, "CRC-32 " + Hex(actual.crc32) + " differs from run.json's " + crc +
                                         ": damaged or changed after the run; rerun, or restore the file");
        }
    }
}

}  // namespace revisit
