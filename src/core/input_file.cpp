#include "core/input_file.hpp"

#include "core/error.hpp"

namespace revisit {

std::ifstream OpenForReading(const std::filesystem::path& file, std::ios::openmode mode) {
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (ec || !std::filesystem::exists(status)) throw DatasetError(file, "no such file");
    if (std::filesystem::is_directory(status)) throw DatasetError(file, "is a folder, expected a file");
    if (!std::filesystem::is_regular_file(status)) throw DatasetError(file, "not a regular file");
    std::ifstream in(file, mode | std::ios::in);
    if (!in) throw DatasetError(file, "cannot open for reading");
    return in;
}

}  // namespace revisit
