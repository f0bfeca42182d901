#pragma once
/// The deleting discipline, the counterpart of core/atomic_file.hpp: revisit removes only regular
/// files of the names it writes itself, in a folder it reaches without a symbolic link, and never
/// anything through a link (a linked folder is refused, a linked file is left alone).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace revisit {

/// Throws DatasetError naming `folder` when it is a symbolic link: writing or deleting there would
/// touch a folder outside the run. A missing folder is fine (it is created as a real one).
void RefuseLinkedFolder(const std::filesystem::path& folder);

/// Removes the regular files directly in `folder` whose extension is one of `extensions` (".html").
/// Refuses a linked `folder` (RefuseLinkedFolder); links, folders and other files in it are kept.
/// Returns how many files were removed; throws DatasetError naming a file that cannot be removed.
std::size_t RemoveOwnFiles(const std::filesystem::path& folder, const std::vector<std::string>& extensions);

/// The same for the regular files directly in `folder` whose file name `is_own` accepts.
std::size_t RemoveOwnFilesIf(const std::filesystem::path& folder, const std::function<bool(const std::string& name)>& is_own);

/// Removes `file` when it is a regular file (a link of that name and its target are kept). Returns
/// whether it was removed; throws DatasetError naming a file that cannot be removed.
bool RemoveOwnFile(const std::filesystem::path& file);

/// RemoveOwnFiles, then `folder` itself when nothing else is left in it (a folder holding other
/// files is kept, with them). Returns whether the folder is gone.
bool RemoveOwnFolder(const std::filesystem::path& folder, const std::vector<std::string>& extensions);

}  // namespace revisit
