#pragma once
#include <filesystem>
#include <stdexcept>
#include <string>

namespace revisit {

/// Bad input: names the file, the line when there is one, and the problem.
class DatasetError : public std::runtime_error {
  public:
    DatasetError(const std::filesystem::path& file, const std::string& problem, std::size_t line = 0)
        : std::runtime_error(Format(file, problem, line)), file_(file), line_(line) {}
    const std::filesystem::path& file() const { return file_; }
    std::size_t line() const { return line_; }

  private:
    static std::string Format(const std::filesystem::path& file, const std::string& problem, std::size_t line) {
        std::string where = file.string();
        if (line > 0) where += ":" + std::to_string(line);
        return where + ": " + problem;
    }
    std::filesystem::path file_;
    std::size_t line_ = 0;
};

/// A configuration value or combination that cannot work; names the key.
class ConfigError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

}  // namespace revisit
