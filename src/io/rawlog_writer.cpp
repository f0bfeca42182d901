/// MRPT rawlog writer (observation-only layout).
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>

#include "core/error.hpp"
#include "io/output_folder.hpp"
#include "io/rawlog_scan.hpp"
#include "io/writer.hpp"

namespace revisit {
namespace {

bool IsGzipName(const std::filesystem::path& file) { return file.extension() == ".gz"; }

class RawlogWriter final : public DatasetWriter {
  public:
    RawlogWriter(const std::filesystem::path& file, const WriterOptions& options, bool force)
        : file_(file), options_(options) {
        PrepareOutputFile(file, force);
        if (IsGzipName(file)) {
            auto gz = std::make_unique<mrpt::io::CFileGZOutputStream>();
            if (!gz->open(file.string(), 1)) throw DatasetError(file, "cannot open for writing");
            stream_ = std::move(gz);
        } else {
            auto plain = std::make_unique<mrpt::io::CFileOutputStream>();
            if (!plain->open(file.string())) throw DatasetError(file, "cannot open for writing");
            stream_ = std::move(plain);
        }
        archive_ = std::make_unique<mrpt::serialization::CArchiveStreamBase<mrpt::io::CStream>>(*stream_);
    }
    ~RawlogWriter() override {
        try {
            Finish();
        } catch (...) {  // a destructor must not throw; Finish() reports errors when called explicitly
        }
    }

    void Write(const Scan& scan) override {
        const auto stamp = mrpt::Clock::fromDouble(scan.timestamp);
        if (scan.T_odom_sensor && options_.write_odometry) WriteOdometry(*scan.T_odom_sensor, stamp);
        if (scan.T_world_sensor) {
            auto gt = mrpt::obs::CObservationRobotPose::Create();
            gt->sensorLabel = "GROUND_TRUTH";
            gt->timestamp = stamp;
            gt->pose.mean = ToCPose3D(*scan.T_world_sensor);
            *archive_ << *gt;
        }
        if (options_.planar_as_range_scan) {
            *archive_ << *MakeRangeScan(scan, stamp);
        } else {
            *archive_ << *MakePointCloud(scan, stamp);
        }
    }

    void Finish() override {
        if (!stream_) return;
        archive_.reset();
        stream_.reset();
    }

  private:
    void WriteOdometry(const Eigen::Isometry3d& T_odom, mrpt::Clock::time_point stamp) {
        if (options_.planar_as_range_scan) {  // 2D robots: the classic wheel-odometry observation
            auto odo = mrpt::obs::CObservationOdometry::Create();
            odo->sensorLabel = "ODOMETRY";
            odo->timestamp = stamp;
            odo->odometry = mrpt::poses::CPose2D(ToCPose3D(T_odom));
            *archive_ << *odo;
            return;
        }
        auto pose = mrpt::obs::CObservationRobotPose::Create();
        pose->sensorLabel = "ODOMETRY";
        pose->timestamp = stamp;
        pose->pose.mean = ToCPose3D(T_odom);
        *archive_ << *pose;
    }

    static mrpt::obs::CObservationPointCloud::Ptr MakePointCloud(const Scan& scan, mrpt::Clock::time_point stamp) {
        auto obs = mrpt::obs::CObservationPointCloud::Create();
        obs->sensorLabel = scan.sensor_label.empty() ? "LIDAR" : scan.sensor_label;
        obs->timestamp = stamp;
        const std::size_t n = scan.points.size();
        if (scan.has_intensities()) {
            auto map = mrpt::maps::CPointsMapXYZI::Create();
            map->resize(n);
            for (std::size_t i = 0; i < n; ++i) {
                map->setPointFast(i, scan.points[i].x(), scan.points[i].y(), scan.points[i].z());
                map->setPointIntensity(i, scan.intensities[i]);
            }
            obs->pointcloud = map;
        } else {
            auto map = mrpt::maps::CSimplePointsMap::Create();
            map->resize(n);
            for (std::size_t i = 0; i < n; ++i) map->setPointFast(i, scan.points[i].x(), scan.points[i].y(), scan.points[i].z());
            obs->pointcloud = map;
        }
        return obs;
    }

    mrpt::obs::CObservation2DRangeScan::Ptr MakeRangeScan(const Scan& scan, mrpt::Clock::time_point stamp) const {
        auto obs = mrpt::obs::CObservation2DRangeScan::Create();
        obs->sensorLabel = scan.sensor_label.empty() ? "LASER" : scan.sensor_label;
        obs->timestamp = stamp;
        obs->aperture = static_cast<float>(options_.planar_stated_aperture > 0.0 ? options_.planar_stated_aperture : options_.planar_aperture);
        obs->rightToLeft = true;
        obs->maxRange = static_cast<float>(options_.planar_max_range);
        const int beams = options_.planar_beams;
        obs->resizeScanAndAssign(beams, obs->maxRange, false);
        // Beam i points at -aperture/2 + i * aperture / (beams - 1), as CObservation2DRangeScan::getScanAngle.
        const double step = options_.planar_aperture / (beams - 1);
        for (const auto& p : scan.points) {
            const double angle = std::atan2(p.y(), p.x()) + options_.planar_aperture / 2.0;
            const long beam = std::lround(angle / step);
            if (beam < 0 || beam >= beams) continue;
            obs->setScanRange(beam, std::hypot(p.x(), p.y()));
            obs->setScanRangeValidity(beam, true);
        }
        return obs;
    }

    std::filesystem::path file_;
    WriterOptions options_;
    std::unique_ptr<mrpt::io::CStream> stream_;
    std::unique_ptr<mrpt::serialization::CArchiveStreamBase<mrpt::io::CStream>> archive_;
};

}  // namespace

std::unique_ptr<DatasetWriter> CreateRawlogWriter(const std::filesystem::path& file, const WriterOptions& options,
                                                  bool force) {
    return std::make_unique<RawlogWriter>(file, options, force);
}

}  // namespace revisit
