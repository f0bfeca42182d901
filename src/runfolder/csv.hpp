#pragma once
/// Minimal CSV for the run folder: comma-separated, a header row, no quoting (fields never contain
/// commas: free text is sanitized on write).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace revisit {

class CsvRow {
  public:
    CsvRow& Add(const std::string& value);
    CsvRow& Add(double value);
    CsvRow& Add(long long value);
    CsvRow& Add(std::size_t value) { return Add(static_cast<long long>(value)); }
    CsvRow& Add(int value) { return Add(static_cast<long long>(value)); }
    CsvRow& Add(bool value) { return Add(static_cast<long long>(value ? 1 : 0)); }
    /// 12 fields: the top three rows of the 4x4 matrix, row-major (as KITTI poses).
    CsvRow& AddPose(const Eigen::Isometry3d& T);
    std::string Text() const;

  private:
    std::vector<std::string> fields_;
};

/// Header names for a pose written by AddPose: prefix_00 .. prefix_23.
std::vector<std::string> PoseColumns(const std::string& prefix);

/// A parsed CSV file: rows of named fields. Errors name the file and line.
class CsvTable {
  public:
    static CsvTable Read(const std::filesystem::path& file);
    std::size_t size() const { return rows_.size(); }
    const std::string& Text(std::size_t row, const std::string& column) const;
    /// A finite number; NaN, infinity or text is a DatasetError naming the file, line and column.
    double Number(std::size_t row, const std::string& column) const;
    long long Integer(std::size_t row, const std::string& column) const;
    /// An integer in [0, end), e.g. a scan index.
    std::size_t Index(std::size_t row, const std::string& column, std::size_t end) const;
    /// 12 columns prefix_00 .. prefix_23; a rotation part that is not a rotation is an error.
    Eigen::Isometry3d Pose(std::size_t row, const std::string& prefix) const;
    const std::filesystem::path& file() const { return file_; }

  private:
    std::filesystem::path file_;
    std::map<std::string, std::size_t> columns_;
    std::vector<std::vector<std::string>> rows_;
};

}  // namespace revisit
