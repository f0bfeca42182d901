#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <random>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void ThrowSystemError(const fs::path& file, const char* what, int error) {
    throw DatasetError(file, std::string(what) + ": " + std::strerror(error));
}

/// `.name.tmp-RANDOM` in the same folder (a rename within one file system is atomic). The name cannot
/// be predicted, and it is created with O_EXCL | O_NOFOLLOW: whatever already has it is never opened.
int CreateTemporaryFor(const fs::path& file, fs::path& temporary) {
    static std::mutex mutex;
    static std::mt19937_64 random{std::random_device{}()};
    std::string stem = file.filename().string();
    if (stem.size() > 200) stem.resize(200);  // room for the prefix and suffix within NAME_MAX
    for (int attempt = 0; attempt < 100; ++attempt) {
        std::uint64_t value = 0;
        {
            const std::lock_guard<std::mutex> lock(mutex);
            value = random();
        }
        char suffix[17];
        std::snprintf(suffix, sizeof(suffix), "%016llx", static_cast<unsigned long long>(value));
        const std::string name = "." + stem + ".tmp-" + suffix;
        temporary = file.has_parent_path() ? file.parent_path() / name : fs::path(name);
        const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd >= 0) return fd;
        if (errno != EEXIST) ThrowSystemError(file, "cannot create a temporary file for writing", errno);
    }
    ThrowSystemError(file, "cannot create a temporary file for writing", EEXIST);
}

/// write(2) until every byte is out: short writes are retried, errors (ENOSPC, EFBIG, EIO) thrown.
void WriteAll(int fd, std::string_view bytes, const fs::path& file) {
    const char* data = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
        const ssize_t written = ::write(fd, data, left);
        if (written < 0) {
            if (errno == EINTR) continue;
            ThrowSystemError(file, "cannot write", errno);
        }
        data += written;
        left -= static_cast<std::size_t>(written);
    }
}

}  // namespace

TemporaryPath::TemporaryPath(fs::path file) : file_(std::move(file)) {
    if (file_.empty()) throw DatasetError(file_, "no output file name given");
    fd_ = CreateTemporaryFor(file_, temporary_);
}

TemporaryPath::~TemporaryPath() {
    if (fd_ >= 0) ::close(fd_);
    if (committed_) return;
    std::error_code ignored;
    fs::remove(temporary_, ignored);  // the name this object created: a file, never a link's target
}

int TemporaryPath::ReleaseDescriptor() {
    const int fd = fd_;
    fd_ = -1;
    return fd;
}

void TemporaryPath::Commit() {
    if (fd_ >= 0) {
        const int fd = ReleaseDescriptor();
        // close() can report a deferred write error (NFS, quota): checked like every write.
        if (::close(fd) != 0) ThrowSystemError(file_, "cannot write", errno);
    }
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(temporary_, ec)))
        throw DatasetError(file_, "was not written (no temporary file)");
    fs::rename(temporary_, file_, ec);
    if (ec) throw DatasetError(file_, "cannot move into place: " + ec.message());
    committed_ = true;
}

int CreateFileExclusively(const fs::path& file) {
    if (file.empty()) throw DatasetError(file, "no output file name given");
    struct stat st {};
    if (::lstat(file.c_str(), &st) == 0) {
        if (S_ISDIR(st.st_mode)) throw DatasetError(file, "is a folder, expected a file name");
        if (::unlink(file.c_str()) != 0 && errno != ENOENT) ThrowSystemError(file, "cannot replace", errno);
    }
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0) ThrowSystemError(file, "cannot create for writing", errno);
    return fd;
}

void WriteFileAtomically(const fs::path& file, std::string_view bytes) {
    TemporaryPath temporary(file);
    WriteAll(temporary.descriptor(), bytes, file);
    temporary.Commit();
}

void WriteFileAtomically(const fs::path& file, const std::function<void(std::ostream&)>& fill) {
    std::ostringstream out;
    fill(out);
    if (!out) throw DatasetError(file, "cannot format the content");
    WriteFileAtomically(file, out.str());
}

}  // namespace revisit
