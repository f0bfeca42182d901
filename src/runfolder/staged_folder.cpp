#include "runfolder/staged_folder.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "core/error.hpp"
#include "core/owned_files.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

/// A new empty folder `.NAME.KIND-XXXXXX` beside `target`, created by mkdtemp (O_EXCL semantics).
fs::path MakeFolderBeside(const fs::path& target, const std::string& kind) {
    const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::string pattern = (parent / ("." + target.filename().string() + "." + kind + "-XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) {
        throw DatasetError(target, "cannot create a folder beside it: " + std::string(std::strerror(errno)));
    }
    return pattern;
}

}  // namespace

StagedFolder::StagedFolder(fs::path target, std::vector<std::string> own_extensions)
    : target_(std::move(target)), own_extensions_(std::move(own_extensions)) {
    RefuseLinkedFolder(target_);
    std::error_code ec;
    if (target_.has_parent_path()) fs::create_directories(target_.parent_path(), ec);
    if (ec) throw DatasetError(target_.parent_path(), "cannot create folder: " + ec.message());
    staged_ = MakeFolderBeside(target_, "staged");
    // mkdtemp makes the folder private (0700); the report is read as any folder the user makes is.
    const mode_t mask = ::umask(0);
    ::umask(mask);
    fs::permissions(staged_, static_cast<fs::perms>(0777 & ~mask), ec);
}

StagedFolder::~StagedFolder() {
    if (committed_) return;
    try {
        RemoveOwnFolder(staged_, own_extensions_);
    } catch (...) {  // a destructor cannot report; the staged folder is hidden and named for what it is
    }
}

fs::path StagedFolder::Commit() {
    RefuseLinkedFolder(target_);  // checked again: the old folder is renamed, never followed
    std::error_code ec;
    fs::path old;
    const auto status = fs::symlink_status(target_, ec);
    if (fs::exists(status)) {
        if (!fs::is_directory(status)) throw DatasetError(target_, "exists and is not a folder; remove it to write the new one");
        // The old folder moves to a fresh name (rename(2) over an empty mkdtemp folder is atomic).
        old = MakeFolderBeside(target_, "previous");
        fs::rename(target_, old, ec);
        if (ec) {
            fs::remove(old, ec);
            throw DatasetError(target_, "cannot move the old folder aside: " + ec.message());
        }
    }
    fs::rename(staged_, target_, ec);
    if (ec) {
        const std::string reason = ec.message();
        if (!old.empty()) fs::rename(old, target_, ec);  // put the old one back
        throw DatasetError(target_, "cannot move the new folder into place: " + reason);
    }
    committed_ = true;
    if (old.empty() || RemoveOwnFolder(old, own_extensions_)) return {};
    return old;
}

}  // namespace revisit
