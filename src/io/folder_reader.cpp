#include "io/folder_reader.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/se3.hpp"
#include "io/cloud_files.hpp"
#include "io/trajectory_io.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

constexpr double kDefaultScanPeriod = 0.1;  ///< [s] assumed when a dataset has no times (10 Hz LiDAR)

std::vector<fs::path> FilesWithExtension(const fs::path& folder, const std::string& extension) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder)) {
        if (entry.is_regular_file() && entry.path().extension() == extension) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

/// One scan file per index, with optional reference poses and times resolved up front.
class FolderReader final : public Reader {
  public:
    using Loader = CloudData (*)(const fs::path&);

    FolderReader(DatasetInfo info, std::vector<fs::path> files, Loader loader, std::string label,
                 const ReaderOptions& options)
        : info_(std::move(info)), files_(std::move(files)), loader_(loader), label_(std::move(label)),
          vertical_correction_(options.kitti_vertical_correction) {
        info_.num_scans = files_.size();
    }

    /// Reference poses and times. KITTI poses (no times) pair by index: one per file. TUM poses pair
    /// by time stamp with the folder's times.txt, interpolated (io/timed_poses.hpp); without
    /// times.txt they pair by index and give the scans their times.
    void SetPosesAndTimes(Trajectory reference, std::vector<double> times, const fs::path& times_file,
                          const TimePairingConfig& pairing) {
        if (!times.empty() && times.size() != files_.size()) {
            throw DatasetError(times_file, std::to_string(times.size()) + " times for " +
                                               std::to_string(files_.size()) + " scans");
        }
        if (reference.has_timestamps() && !times.empty()) {
            info_.has_reference_poses = true;
            timed_reference_.emplace(std::move(reference), pairing);
            times_ = std::move(times);
            return;
        }
        if (!reference.empty() && reference.size() != files_.size()) {
            throw DatasetError(info_.poses_file, std::to_string(reference.size()) + " poses for " +
                                                     std::to_string(files_.size()) + " scans" +
                                                     (reference.has_timestamps()
                                                          ? " (TUM poses pair by time stamp, but the folder has no times.txt)"
                                                          : " (KITTI poses pair with scans by index)"));
        }
        if (times.empty() && reference.has_timestamps()) times = reference.timestamps;
        info_.has_reference_poses = !reference.empty();
        reference_ = std::move(reference.poses);
        times_ = std::move(times);
    }

    std::optional<Scan> Next() override {
        if (next_ >= files_.size()) return std::nullopt;
        const std::size_t i = next_++;
        CloudData cloud = loader_(files_[i]);
        if (vertical_correction_) ApplyKittiVerticalCorrection(cloud.points);
        Scan scan;
        scan.index = i;
        scan.timestamp = times_.empty() ? kDefaultScanPeriod * static_cast<double>(i) : times_[i];
        scan.sensor_label = label_;
        scan.points = std::move(cloud.points);
        scan.intensities = std::move(cloud.intensities);
        scan.point_times = std::move(cloud.point_times);
        if (!reference_.empty()) scan.T_world_sensor = reference_[i];
        if (timed_reference_) scan.T_world_sensor = timed_reference_->At(scan.timestamp);
        stats_.scans++;
        stats_.points += scan.points.size();
        stats_.non_finite_points += cloud.non_finite;
        return scan;
    }

    bool SkipTo(std::size_t index) override {
        const std::size_t to = std::min(index, files_.size());
        if (to > next_) {
            stats_.scans += to - next_;
            next_ = to;
        }
        return true;
    }

    const DatasetInfo& Info() const override { return info_; }

  private:
    DatasetInfo info_;
    std::vector<fs::path> files_;
    Loader loader_;
    std::string label_;
    bool vertical_correction_;
    Poses reference_;
    std::optional<TimedPoses> timed_reference_;
    std::vector<double> times_;
    std::size_t next_ = 0;
};

fs::path FirstExisting(std::initializer_list<fs::path> candidates) {
    for (const auto& candidate : candidates) {
        if (!candidate.empty() && fs::is_regular_file(candidate)) return candidate;
    }
    return {};
}

fs::path KittiRoot(const fs::path& path) {
    return path.filename() == "velodyne" ? path.parent_path() : path;
}

}  // namespace

std::optional<Eigen::Isometry3d> ReadKittiTr(const fs::path& calib) {
    std::ifstream in(calib);
    std::string line;
    for (std::size_t line_number = 1; std::getline(in, line); ++line_number) {
        if (line.rfind("Tr:", 0) != 0) continue;
        std::istringstream values(line.substr(3));
        Eigen::Matrix<double, 3, 4> M;
        for (int i = 0; i < 12; ++i) {
            if (!(values >> M(i / 4, i % 4))) throw DatasetError(calib, "Tr needs 12 numbers", line_number);
        }
        // calib.txt rounds Tr to a few digits: re-orthonormalize so that Tr.inverse() is exact.
        Eigen::Isometry3d Tr = Eigen::Isometry3d::Identity();
        Tr.linear() = NearestRotation(M.leftCols<3>());
        if ((Tr.linear() - M.leftCols<3>()).norm() > 1e-2) {
            throw DatasetError(calib, "Tr's rotation part is not a rotation matrix", line_number);
        }
        Tr.translation() = M.col(3);
        return Tr;
    }
    return std::nullopt;
}

bool IsKittiFolder(const fs::path& path) {
    const fs::path velodyne = KittiRoot(path) / "velodyne";
    return fs::is_directory(velodyne) && !FilesWithExtension(velodyne, ".bin").empty();
}

std::unique_ptr<Reader> OpenKittiFolder(const fs::path& path, const ReaderOptions& options) {
    const fs::path root = KittiRoot(path);
    auto files = FilesWithExtension(root / "velodyne", ".bin");
    DatasetInfo info{"kitti", path, files.size(), false, {}, {}, {}};
    // The official layout keeps ground truth apart: <root>/sequences/NN and <root>/poses/NN.txt.
    const fs::path official = root.parent_path().filename() == "sequences"
                                  ? root.parent_path().parent_path() / "poses" / (root.filename().string() + ".txt")
                                  : fs::path();
    info.poses_file = FirstExisting({options.poses_file, root / "poses.txt", official});
    if (!options.poses_file.empty() && info.poses_file != options.poses_file) {
        throw DatasetError(options.poses_file, "no such poses file");
    }
    Trajectory reference;
    if (!info.poses_file.empty()) {
        reference = ReadPoses(info.poses_file);
        if (const auto Tr = ReadKittiTr(root / "calib.txt")) {
            const Eigen::Isometry3d Tr_inv = Tr->inverse();
            for (auto& P : reference.poses) P = Tr_inv * P * *Tr;
        }
    }
    const fs::path times_file = root / "times.txt";
    auto reader = std::make_unique<FolderReader>(info, std::move(files), &LoadKittiBin, "VELODYNE", options);
    reader->SetPosesAndTimes(std::move(reference), fs::is_regular_file(times_file) ? ReadTimes(times_file)
                                                                                    : std::vector<double>{},
                             times_file, options.pose_pairing);
    return reader;
}

std::unique_ptr<Reader> OpenStampedScanFiles(DatasetInfo info, std::vector<fs::path> files, CloudLoader loader, std::string label,
                                             std::vector<double> times, Trajectory reference, const ReaderOptions& options) {
    auto reader = std::make_unique<FolderReader>(std::move(info), std::move(files), loader, std::move(label), options);
    reader->SetPosesAndTimes(std::move(reference), std::move(times), {}, options.pose_pairing);
    return reader;
}

std::unique_ptr<Reader> OpenCloudFolder(const fs::path& path, const ReaderOptions& options) {
    auto pcd = FilesWithExtension(path, ".pcd");
    auto ply = FilesWithExtension(path, ".ply");
    if (pcd.empty() && ply.empty()) {
        throw DatasetError(path, "no scans found: expected velodyne/*.bin (KITTI), *.pcd or *.ply files");
    }
    if (!pcd.empty() && !ply.empty()) throw DatasetError(path, "folder mixes .pcd and .ply files; keep one format");
    const bool is_pcd = !pcd.empty();
    DatasetInfo info{is_pcd ? "pcd" : "ply", path, std::nullopt, false, {}, {}, {}};
    info.poses_file = FirstExisting({options.poses_file, path / "poses.txt", path / "poses_tum.txt"});
    if (!options.poses_file.empty() && info.poses_file != options.poses_file) {
        throw DatasetError(options.poses_file, "no such poses file");
    }
    const fs::path times_file = path / "times.txt";
    auto reader = std::make_unique<FolderReader>(info, is_pcd ? std::move(pcd) : std::move(ply),
                                                 is_pcd ? &LoadPcd : &LoadPly, "LIDAR", options);
    reader->SetPosesAndTimes(info.poses_file.empty() ? Trajectory{} : ReadPoses(info.poses_file),
                             fs::is_regular_file(times_file) ? ReadTimes(times_file) : std::vector<double>{},
                             times_file, options.pose_pairing);
    return reader;
}

}  // namespace revisit
