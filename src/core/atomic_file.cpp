#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

/// `.name.tmp-PID-N` in the same folder: a rename within one file system is atomic.
fs::path TemporaryNameFor(const fs::path& file) {
    static std::atomic<unsigned> counter{0};
    const std::string name = "." + file.filename().string() + ".tmp-" + std::to_string(getpid()) + "-" +
                             std::to_string(counter.fetch_add(1));
    return file.has_parent_path() ? file.parent_path() / name : fs::path(name);
}

[[noreturn]] void ThrowSystemError(const fs::path& file, const char* what, int error) {
    throw DatasetError(file, std::string(what) + ": " + std::strerror(error));
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

TemporaryPath::TemporaryPath(fs::path file) : file_(std::move(file)), temporary_(TemporaryNameFor(file_)) {
    if (file_.empty()) throw DatasetError(file_, "no output file name given");
}

TemporaryPath::~TemporaryPath() {
    if (committed_) return;
    std::error_code ignored;
    fs::remove(temporary_, ignored);
}

void TemporaryPath::Commit() {
    std::error_code ec;
    if (!fs::is_regular_file(temporary_, ec)) throw DatasetError(file_, "was not written (no temporary file)");
    fs::rename(temporary_, file_, ec);
    if (ec) throw DatasetError(file_, "cannot move into place: " + ec.message());
    committed_ = true;
}

void WriteFileAtomically(const fs::path& file, std::string_view bytes) {
    TemporaryPath temporary(file);
    const int fd = ::open(temporary.path().c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) ThrowSystemError(file, "cannot open for writing", errno);
    try {
        WriteAll(fd, bytes, file);
    } catch (...) {
        ::close(fd);
        throw;
    }
    // close() can report a deferred write error (NFS, quota): checked like every write.
    if (::close(fd) != 0) ThrowSystemError(file, "cannot write", errno);
    temporary.Commit();
}

void WriteFileAtomically(const fs::path& file, const std::function<void(std::ostream&)>& fill) {
    std::ostringstream out;
    fill(out);
    if (!out) throw DatasetError(file, "cannot format the content");
    WriteFileAtomically(file, out.str());
}

}  // namespace revisit
