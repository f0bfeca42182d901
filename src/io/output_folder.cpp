#include "io/output_folder.hpp"

#include "core/error.hpp"

namespace revisit {
namespace fs = std::filesystem;

void PrepareOutputFolder(const fs::path& folder, bool force) {
    if (folder.empty()) throw DatasetError(folder, "no output folder given");
    std::error_code ec;
    if (fs::exists(folder)) {
        if (!fs::is_directory(folder)) throw DatasetError(folder, "exists and is not a folder");
        if (!fs::is_empty(folder) && !force) {
            throw DatasetError(folder, "output folder is not empty; choose another or pass --force to write into it");
        }
    }
    fs::create_directories(folder, ec);
    if (ec) throw DatasetError(folder, "cannot create folder: " + ec.message());
}

namespace {
/// True when `inner` is `outer` or below it (both canonical).
bool IsWithin(const fs::path& inner, const fs::path& outer) {
    auto o = outer.begin();
    for (auto i = inner.begin(); o != outer.end(); ++i, ++o) {
        if (i == inner.end() || *i != *o) return false;
    }
    return true;
}
}  // namespace

void RefuseOutputOverInput(const fs::path& input, const fs::path& output) {
    std::error_code ec;
    if (!fs::exists(output, ec) || !fs::exists(input, ec)) return;
    const fs::path in = fs::canonical(input, ec);
    const fs::path out = ec ? fs::path() : fs::canonical(output, ec);
    if (fs::equivalent(input, output, ec) || (!in.empty() && !out.empty() && IsWithin(in, out))) {
        throw DatasetError(output, "is the input " + input.string() + " (or contains it); writing it would destroy the input");
    }
}

void RefuseOutputInOrOverInput(const fs::path& input, const fs::path& output) {
    RefuseOutputOverInput(input, output);
    std::error_code ec;
    if (!fs::is_directory(input, ec)) return;
    const fs::path in = fs::canonical(input, ec);
    if (ec) return;
    const fs::path out = fs::weakly_canonical(fs::absolute(output, ec), ec);
    if (!ec && IsWithin(out, in)) {
        throw DatasetError(output, "is inside the input " + input.string() +
                                       "; writing there would add files to the input: choose an output folder outside it");
    }
}

void PrepareOutputFile(const fs::path& file, bool force) {
    if (file.empty()) throw DatasetError(file, "no output file given");
    if (fs::exists(file) && !force) throw DatasetError(file, "file exists; choose another name or pass --force");
    if (fs::is_directory(file)) throw DatasetError(file, "is a folder, expected a file name");
    std::error_code ec;
    if (file.has_parent_path()) fs::create_directories(file.parent_path(), ec);
    if (ec) throw DatasetError(file.parent_path(), "cannot create folder: " + ec.message());
}

}  // namespace revisit
