#include "runfolder/csv.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/input_file.hpp"
#include "core/error.hpp"
#include "core/se3.hpp"

namespace revisit {

CsvRow& CsvRow::Add(const std::string& value) {
    std::string clean = value;
    for (char& c : clean) {
        if (c == ',' || c == '\n' || c == '\r') c = ';';
    }
    fields_.push_back(clean);
    return *this;
}

CsvRow& CsvRow::Add(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.9g", value);
    fields_.emplace_back(text);
    return *this;
}

CsvRow& CsvRow::Add(long long value) {
    fields_.push_back(std::to_string(value));
    return *this;
}

CsvRow& CsvRow::AddPose(const Eigen::Isometry3d& T) {
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) Add(T.matrix()(r, c));
    }
    return *this;
}

std::string CsvRow::Text() const {
    std::string line;
    for (std::size_t i = 0; i < fields_.size(); ++i) line += (i ? "," : "") + fields_[i];
    return line;
}

std::vector<std::string> PoseColumns(const std::string& prefix) {
    std::vector<std::string> names;
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) names.push_back(prefix + "_" + std::to_string(r) + std::to_string(c));
    }
    return names;
}

CsvTable CsvTable::Read(const std::filesystem::path& file) {
    std::ifstream in = OpenForReading(file);
    CsvTable table;
    table.file_ = file;
    std::string line;
    const auto split = [](const std::string& text) {
        std::vector<std::string> fields;
        std::stringstream stream(text);
        for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
        if (!text.empty() && text.back() == ',') fields.emplace_back();
        return fields;
    };
    if (!std::getline(in, line)) throw DatasetError(file, "empty CSV (no header)");
    const auto header = split(line);
    for (std::size_t i = 0; i < header.size(); ++i) table.columns_[header[i]] = i;
    for (std::size_t line_number = 2; std::getline(in, line); ++line_number) {
        if (line.empty()) continue;
        auto fields = split(line);
        if (fields.size() != header.size()) {
            throw DatasetError(file, "expected " + std::to_string(header.size()) + " fields, found " +
                                         std::to_string(fields.size()), line_number);
        }
        table.rows_.push_back(std::move(fields));
    }
    return table;
}

const std::string& CsvTable::Text(std::size_t row, const std::string& column) const {
    const auto it = columns_.find(column);
    if (it == columns_.end()) throw DatasetError(file_, "missing column '" + column + "'");
    return rows_.at(row)[it->second];
}

double CsvTable::Number(std::size_t row, const std::string& column) const {
    const std::string& text = Text(row, column);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0') {
        throw DatasetError(file_, "column '" + column + "': not a number: '" + text + "'", row + 2);
    }
    // The run folder never holds NaN or infinity: one is damage, named before it reaches a solver.
    if (!std::isfinite(value)) throw DatasetError(file_, "column '" + column + "': not finite: '" + text + "'", row + 2);
    return value;
}

long long CsvTable::Integer(std::size_t row, const std::string& column) const {
    const std::string& text = Text(row, column);
    char* end = nullptr;
    errno = 0;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (end == text.c_str() || *end != '\0' || errno == ERANGE) {
        throw DatasetError(file_, "column '" + column + "': not an integer: '" + text + "'", row + 2);
    }
    return value;
}

std::size_t CsvTable::Index(std::size_t row, const std::string& column, std::size_t end) const {
    const long long value = Integer(row, column);
    if (value < 0 || static_cast<unsigned long long>(value) >= end) {
        throw DatasetError(file_, "column '" + column + "': " + std::to_string(value) + " is outside 0 .. " +
                                      std::to_string(end == 0 ? 0 : end - 1), row + 2);
    }
    return static_cast<std::size_t>(value);
}

Eigen::Isometry3d CsvTable::Pose(std::size_t row, const std::string& prefix) const {
    const auto names = PoseColumns(prefix);
    Eigen::Matrix<double, 3, 4> M;
    for (int i = 0; i < 12; ++i) M(i / 4, i % 4) = Number(row, names[i]);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = NearestRotation(M.leftCols<3>());
    // Written with 9 digits: a rotation part farther than rounding from a rotation is damage.
    if ((T.linear() - M.leftCols<3>()).norm() > 1e-2) {
        throw DatasetError(file_, "columns '" + prefix + "_*': not a rotation matrix", row + 2);
    }
    T.translation() = M.col(3);
    return T;
}

}  // namespace revisit
