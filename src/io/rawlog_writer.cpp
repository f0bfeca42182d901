/// MRPT rawlog writer (observation-only layout).
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/serialization/CArchive.h>

#include <unistd.h>
#include <zlib.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <optional>

#include "core/atomic_file.hpp"
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
        // Objects are serialized in memory and written through zlib ourselves, so that every write and
        // the final close are checked (a full disk names the file) and only a complete rawlog is
        // renamed over `file` (core/atomic_file.hpp).
        temporary_.emplace(file);
        const int fd = temporary_->ReleaseDescriptor();  // zlib owns and closes it from here
        out_ = gzdopen(fd, IsGzipName(file) ? "wb1" : "wbT");
        if (!out_) {
            ::close(fd);
            throw DatasetError(file, "cannot open for writing");
        }
    }
    ~RawlogWriter() override {
        if (out_) gzclose(out_);  // without Finish(): abandoned, the temporary is removed by temporary_
    }
    RawlogWriter(const RawlogWriter&) = delete;
    RawlogWriter& operator=(const RawlogWriter&) = delete;

    void Write(const Scan& scan) override {
        if (!out_) throw DatasetError(file_, "writer already finished");
        const auto stamp = mrpt::Clock::fromDouble(scan.timestamp);
        if (scan.T_odom_sensor && options_.write_odometry) WriteOdometry(*scan.T_odom_sensor, stamp);
        if (scan.T_world_sensor) {
            auto gt = mrpt::obs::CObservationRobotPose::Create();
            gt->sensorLabel = "GROUND_TRUTH";
            gt->timestamp = stamp;
            gt->pose.mean = ToCPose3D(*scan.T_world_sensor);
            Append(*gt);
        }
        if (options_.planar_as_range_scan) {
            Append(*MakeRangeScan(scan, stamp));
        } else {
            Append(*MakePointCloud(scan, stamp));
        }
    }

    void Finish() override {
        if (!out_) return;
        gzFile out = out_;
        out_ = nullptr;
        int errnum = Z_OK;
        const std::string error = gzerror(out, &errnum);
        if (gzclose(out) != Z_OK || errnum != Z_OK) {
            throw DatasetError(file_, "cannot write: " + (errnum != Z_OK ? error : std::string(std::strerror(errno))));
        }
        temporary_->Commit();
    }

  private:
    void Append(const mrpt::serialization::CSerializable& object) {
        mrpt::io::CMemoryStream buffer;
        auto archive = mrpt::serialization::archiveFrom(buffer);
        archive << object;
        const auto size = static_cast<unsigned>(buffer.getTotalBytesCount());
        if (size > 0 && gzwrite(out_, buffer.getRawBufferData(), size) != static_cast<int>(size)) {
            int errnum = Z_OK;
            const char* message = gzerror(out_, &errnum);
            throw DatasetError(file_, std::string("cannot write: ") + (errnum == Z_ERRNO ? std::strerror(errno) : message));
        }
    }

    void WriteOdometry(const Eigen::Isometry3d& T_odom, mrpt::Clock::time_point stamp) {
        if (options_.planar_as_range_scan) {  // 2D robots: the classic wheel-odometry observation
            auto odo = mrpt::obs::CObservationOdometry::Create();
            odo->sensorLabel = "ODOMETRY";
            odo->timestamp = stamp;
            odo->odometry = mrpt::poses::CPose2D(ToCPose3D(T_odom));
            Append(*odo);
            return;
        }
        auto pose = mrpt::obs::CObservationRobotPose::Create();
        pose->sensorLabel = "ODOMETRY";
        pose->timestamp = stamp;
        pose->pose.mean = ToCPose3D(T_odom);
        Append(*pose);
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
    std::optional<TemporaryPath> temporary_;  ///< removed unless Finish() completes
    gzFile out_ = nullptr;
};

}  // namespace

std::unique_ptr<DatasetWriter> CreateRawlogWriter(const std::filesystem::path& file, const WriterOptions& options,
                                                  bool force) {
    return std::make_unique<RawlogWriter>(file, options, force);
}

}  // namespace revisit
