#include "evaluation/scratch_records.hpp"

#include "core/error.hpp"

#include <fcntl.h>
#include <unistd.h>
#include <zstd.h>

#include <cerrno>
#include <cstring>
#include <limits>
#include <string>

namespace revisit {
namespace {

constexpr int kLevel = 1;  // the fastest: the file lives for one run

std::string Problem(const std::string& what) { return what + ": " + std::strerror(errno); }

}  // namespace

ScratchRecords::ScratchRecords(const std::filesystem::path& file, const char* what) : scratch_(file), what_(what) {
    read_fd_ = ::open(scratch_.path().c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (read_fd_ < 0) throw DatasetError(scratch_.path(), Problem(std::string("cannot read back the scratch file of ") + what_ + "s"));
}

ScratchRecords::~ScratchRecords() {
    if (read_fd_ >= 0) ::close(read_fd_);
}

void ScratchRecords::Append(const void* data, std::size_t bytes) {
    if (bytes > std::numeric_limits<std::uint32_t>::max()) throw DatasetError(scratch_.path(), std::string(what_) + " too large for a scratch record");
    std::vector<char> compressed(ZSTD_compressBound(bytes));
    const std::size_t stored = ZSTD_compress(compressed.data(), compressed.size(), data, bytes, kLevel);
    if (ZSTD_isError(stored)) throw DatasetError(scratch_.path(), std::string("zstd: ") + ZSTD_getErrorName(stored));
    for (std::size_t written = 0; written < stored;) {
        const ssize_t n = ::pwrite(scratch_.descriptor(), compressed.data() + written, stored - written, off_t(end_ + written));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw DatasetError(scratch_.path(), Problem(std::string("cannot write a ") + what_));
        written += std::size_t(n);
    }
    places_.push_back({end_, std::uint32_t(stored), std::uint32_t(bytes)});
    end_ += stored;
}

std::vector<std::uint8_t> ScratchRecords::Read(std::size_t k) const {
    const Place& place = places_.at(k);
    std::vector<char> compressed(place.stored);
    for (std::size_t read = 0; read < place.stored;) {
        const ssize_t n = ::pread(read_fd_, compressed.data() + read, place.stored - read, off_t(place.offset + read));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw DatasetError(scratch_.path(), Problem(std::string("cannot read back ") + what_ + " " + std::to_string(k)));
        read += std::size_t(n);
    }
    std::vector<std::uint8_t> record(place.bytes);
    const std::size_t produced = ZSTD_decompress(record.data(), record.size(), compressed.data(), compressed.size());
    // The file is ours and exclusive: anything else means it was damaged while the run held it.
    if (ZSTD_isError(produced) || produced != place.bytes)
        throw DatasetError(scratch_.path(), std::string("damaged scratch record: ") + what_ + " " + std::to_string(k));
    return record;
}

}  // namespace revisit
