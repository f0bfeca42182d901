#include "io/writer.hpp"

#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "io/cloud_files.hpp"
#include "io/output_folder.hpp"
#include "io/trajectory_io.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

class KittiWriter final : public DatasetWriter {
  public:
    KittiWriter(const fs::path& folder, bool force) : folder_(folder) {
        PrepareOutputFolder(folder, force);
        fs::create_directories(folder / "velodyne");
    }
    ~KittiWriter() override = default;  // without Finish(): no times.txt, so a partial folder is not taken as complete

    void Write(const Scan& scan) override {
        std::ostringstream name;
        name << std::setw(6) << std::setfill('0') << count_++ << ".bin";
        SaveKittiBin(folder_ / "velodyne" / name.str(), scan);
        times_.push_back(scan.timestamp);
        if (scan.T_world_sensor) poses_.push_back(*scan.T_world_sensor);
    }

    void Finish() override {
        if (finished_) return;
        finished_ = true;
        WriteTimes(folder_ / "times.txt", times_);
        // Partial ground truth cannot be aligned with the scans by the reader: all or nothing.
        if (!poses_.empty() && poses_.size() == count_) WriteKittiPoses(folder_ / "poses.txt", poses_);
        WriteFileAtomically(folder_ / "calib.txt", std::string_view("Tr: 1 0 0 0 0 1 0 0 0 0 1 0\n"));
    }

  private:
    fs::path folder_;
    std::size_t count_ = 0;
    std::vector<double> times_;
    Poses poses_;
    bool finished_ = false;
};

}  // namespace

std::unique_ptr<DatasetWriter> CreateKittiWriter(const fs::path& folder, bool force) {
    return std::make_unique<KittiWriter>(folder, force);
}

bool HasRawlogExtension(const fs::path& path) {
    const std::string name = path.filename().string();
    const auto ends_with = [&name](const std::string& suffix) {
        return name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    return ends_with(".rawlog") || ends_with(".rawlog.gz");
}

std::unique_ptr<DatasetWriter> CreateWriter(const fs::path& path, const WriterOptions& options, bool force) {
    if (HasRawlogExtension(path)) return CreateRawlogWriter(path, options, force);
    return CreateKittiWriter(path, force);
}

}  // namespace revisit
