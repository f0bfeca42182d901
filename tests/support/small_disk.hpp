#pragma once
/// A real nearly-full disk for write-failure tests: a tmpfs of a few kilobytes mounted on a temporary
/// folder (needs root / CAP_SYS_ADMIN). Tests GTEST_SKIP() when it cannot be mounted.
#include <sys/mount.h>

#include <filesystem>
#include <string>

#include "test_data.hpp"

namespace revisit::test {

class SmallDisk {
  public:
    explicit SmallDisk(std::size_t bytes) {
        const std::string options = "size=" + std::to_string(bytes);
        mounted_ = ::mount("revisit-test", folder_.path().c_str(), "tmpfs", 0, options.c_str()) == 0;
    }
    ~SmallDisk() {
        if (mounted_) ::umount2(folder_.path().c_str(), MNT_DETACH);
    }
    SmallDisk(const SmallDisk&) = delete;
    SmallDisk& operator=(const SmallDisk&) = delete;
    bool mounted() const { return mounted_; }
    const std::filesystem::path& path() const { return folder_.path(); }

  private:
    TempDir folder_;
    bool mounted_ = false;
};

}  // namespace revisit::test
