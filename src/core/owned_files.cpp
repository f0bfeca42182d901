#include "core/owned_files.hpp"

#include <system_error>

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

std::size_t RemoveOwnFiles(const fs::path& folder, std::initializer_list<const char*> extensions) {
    RefuseLinkedFolder(folder);
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(folder, ec))) return 0;
    std::size_t removed = 0;
    for (const auto& entry : fs::directory_iterator(folder)) {
        // symlink_status: a link named *.html is not a file revisit wrote, and its target is never touched.
        if (!fs::is_regular_file(entry.symlink_status())) continue;
        const std::string ext = entry.path().extension().string();
        bool own = false;
        for (const char* e : extensions) own = own || ext == e;
        if (!own) continue;
        if (!fs::remove(entry.path(), ec) && ec) throw DatasetError(entry.path(), "cannot remove: " + ec.message());
        ++removed;
    }
    return removed;
}

}  // namespace revisit
