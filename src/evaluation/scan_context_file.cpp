#include "evaluation/scan_context_file.hpp"

#include "core/error.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

namespace revisit {
namespace {

std::string Problem(const std::string& what) { return what + ": " + std::strerror(errno); }

}  // namespace

ScanContextFile::ScanContextFile(const std::filesystem::path& file, int rows, int cols)
    : scratch_(file), rows_(rows), cols_(cols) {
    read_fd_ = ::open(scratch_.path().c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
    if (read_fd_ < 0) throw DatasetError(scratch_.path(), Problem("cannot read back the scratch file of ScanContext descriptors"));
}

ScanContextFile::~ScanContextFile() {
    if (read_fd_ >= 0) ::close(read_fd_);
}

void ScanContextFile::Add(const ScanContextDescriptor& descriptor) {
    if (descriptor.bins.rows() != rows_ || descriptor.bins.cols() != cols_ || descriptor.sector_key.size() != cols_)
        throw ConfigError("scan context: descriptors of different sizes");
    const std::size_t floats = std::size_t(rows_) * std::size_t(cols_) + std::size_t(cols_);
    std::vector<float> record(floats);
    std::memcpy(record.data(), descriptor.bins.data(), sizeof(float) * std::size_t(rows_) * std::size_t(cols_));
    std::memcpy(record.data() + std::size_t(rows_) * std::size_t(cols_), descriptor.sector_key.data(), sizeof(float) * std::size_t(cols_));
    const std::size_t bytes = sizeof(float) * floats;
    const auto* data = reinterpret_cast<const char*>(record.data());
    for (std::size_t written = 0; written < bytes;) {
        const ssize_t n = ::pwrite(scratch_.descriptor(), data + written, bytes - written, off_t(size() * bytes + written));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw DatasetError(scratch_.path(), Problem("cannot write a ScanContext descriptor"));
        written += std::size_t(n);
    }
    ring_keys_.push_back(descriptor.ring_key);
}

ScanContextDescriptor ScanContextFile::Get(std::size_t scan) const {
    const std::size_t cells = std::size_t(rows_) * std::size_t(cols_);
    const std::size_t bytes = sizeof(float) * (cells + std::size_t(cols_));
    std::vector<float> record(cells + std::size_t(cols_));
    auto* data = reinterpret_cast<char*>(record.data());
    for (std::size_t read = 0; read < bytes;) {
        const ssize_t n = ::pread(read_fd_, data + read, bytes - read, off_t(scan * bytes + read));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) throw DatasetError(scratch_.path(), Problem("cannot read back ScanContext descriptor " + std::to_string(scan)));
        read += std::size_t(n);
    }
    ScanContextDescriptor descriptor;
    descriptor.bins = Eigen::Map<const Eigen::MatrixXf>(record.data(), rows_, cols_);
    descriptor.sector_key = Eigen::Map<const Eigen::VectorXf>(record.data() + cells, cols_);
    descriptor.ring_key = ring_keys_.at(scan);
    return descriptor;
}

}  // namespace revisit
