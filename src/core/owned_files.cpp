#include "core/owned_files.hpp"

#include <algorithm>
#include <system_error>
#include <vector>

#include "core/error.hpp"

namespace revisit {
namespace fs = std::filesystem;

void RefuseLinkedFolder(const fs::path& folder) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(folder, ec))) return;
    const fs::path target = fs::read_symlink(folder, ec);
    throw DatasetError(folder, "is a symbolic link" + (ec ? std::string() : " to " + target.string()) +
                                   "; revisit writes and deletes only inside the run folder: remove the link or point elsewhere");
}

std::size_t RemoveOwnFilesIf(const fs::path& folder, const std::function<bool(const std::string& name)>& is_own) {
    RefuseLinkedFolder(folder);
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(folder, ec))) return 0;
    std::vector<fs::path> own;
    for (const auto& entry : fs::directory_iterator(folder)) {
        // symlink_status: a link named like an own file is not a file revisit wrote, and its target is never touched.
        if (fs::is_regular_file(entry.symlink_status()) && is_own(entry.path().filename().string())) own.push_back(entry.path());
    }
    std::size_t removed = 0;
    for (const auto& file : own) removed += RemoveOwnFile(file);
    return removed;
}

std::size_t RemoveOwnFiles(const fs::path& folder, const std::vector<std::string>& extensions) {
    return RemoveOwnFilesIf(folder, [&extensions](const std::string& name) {
        const std::string ext = fs::path(name).extension().string();
        return std::find(extensions.begin(), extensions.end(), ext) != extensions.end();
    });
}

bool RemoveOwnFile(const fs::path& file) {
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(file, ec))) return false;
    if (!fs::remove(file, ec) && ec) throw DatasetError(file, "cannot remove: " + ec.message());
    return true;
}

bool RemoveOwnFolder(const fs::path& folder, const std::vector<std::string>& extensions) {
    RemoveOwnFiles(folder, extensions);
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(folder, ec))) return !fs::exists(fs::symlink_status(folder, ec));
    if (!fs::is_empty(folder, ec) || ec) return false;
    fs::remove(folder, ec);  // an empty real folder: rmdir(2)
    return !ec;
}

}  // namespace revisit
