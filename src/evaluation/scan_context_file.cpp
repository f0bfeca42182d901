#include "evaluation/scan_context_file.hpp"

#include "core/error.hpp"

#include <cstring>

namespace revisit {

ScanContextFile::ScanContextFile(const std::filesystem::path& file, int rows, int cols)
    : records_(file, "ScanContext descriptor"), rows_(rows), cols_(cols) {}

void ScanContextFile::Add(const ScanContextDescriptor& descriptor) {
    if (descriptor.bins.rows() != rows_ || descriptor.bins.cols() != cols_ || descriptor.sector_key.size() != cols_)
        throw ConfigError("scan context: descriptors of different sizes");
    const std::size_t cells = std::size_t(rows_) * std::size_t(cols_);
    std::vector<float> record(cells + std::size_t(cols_));
    std::memcpy(record.data(), descriptor.bins.data(), sizeof(float) * cells);
    std::memcpy(record.data() + cells, descriptor.sector_key.data(), sizeof(float) * std::size_t(cols_));
    records_.Append(record.data(), sizeof(float) * record.size());
    ring_keys_.push_back(descriptor.ring_key);
}

ScanContextDescriptor ScanContextFile::Get(std::size_t scan) const {
    const std::size_t cells = std::size_t(rows_) * std::size_t(cols_);
    const std::vector<std::uint8_t> bytes = records_.Read(scan);
    std::vector<float> record(cells + std::size_t(cols_));
    if (bytes.size() != sizeof(float) * record.size())
        throw DatasetError(records_.path(), "scan context " + std::to_string(scan) + ": a scratch record of " + std::to_string(bytes.size()) + " bytes");
    std::memcpy(record.data(), bytes.data(), bytes.size());
    ScanContextDescriptor descriptor;
    descriptor.bins = Eigen::Map<const Eigen::MatrixXf>(record.data(), rows_, cols_);
    descriptor.sector_key = Eigen::Map<const Eigen::VectorXf>(record.data() + cells, cols_);
    descriptor.ring_key = ring_keys_.at(scan);
    return descriptor;
}

}  // namespace revisit
