#pragma once
/// Where tests find real data, and a scratch folder that cleans up after itself.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

namespace revisit::test {

inline std::filesystem::path SharedData(const std::string& relative) {
    return std::filesystem::path(REVISIT_SHARED_DIR) / "data" / relative;
}
inline std::filesystem::path MrptDataset(const std::string& name) {
    return std::filesystem::path(REVISIT_MRPT_DATASETS) / name;
}

/// A whole file's bytes (empty when it cannot be read).
inline std::string ReadFile(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Skips the calling test when a data file or folder is absent (e.g. no ../shared on a user's machine).
#define REVISIT_REQUIRE_DATA(path)                                                                       \
    do {                                                                                                 \
        if (!std::filesystem::exists(path)) GTEST_SKIP() << "test data not available: " << (path).string(); \
    } while (0)

class TempDir {
  public:
    TempDir() {
        std::random_device device;
        path_ = std::filesystem::temp_directory_path() / ("revisit-test-" + std::to_string(device()) + std::to_string(device()));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

  private:
    std::filesystem::path path_;
};

}  // namespace revisit::test
