#pragma once
/// Dataset writers: the formats the readers read back.
#include <filesystem>
#include <memory>

#include "core/scan.hpp"

namespace revisit {

struct WriterOptions {
    /// Rawlogs: store scans as CObservation2DRangeScan instead of CObservationPointCloud.
    /// The points must be planar (z = 0) and come from `planar_beams` beams spread evenly over
    /// `planar_aperture` [rad] centred on +x; beams without a point are stored as invalid.
    bool planar_as_range_scan = false;
    int planar_beams = 360;
    double planar_aperture = 2.0 * 3.14159265358979323846;  ///< [rad]
    double planar_max_range = 30.0;                          ///< [m]
    /// [rad] aperture stated in the file when it differs from the beams' (0: planar_aperture); tests of the
    /// aperture check write files that lie, as the MRPT conversions of CARMEN logs do
    double planar_stated_aperture = 0.0;
    bool write_odometry = true;  ///< rawlogs: CObservationOdometry before each scan that has T_odom_sensor
};

class DatasetWriter {
  public:
    virtual ~DatasetWriter() = default;
    virtual void Write(const Scan& scan) = 0;
    /// Writes what is kept until the end (poses.txt, times.txt) and closes files. Only a finished output
    /// is complete: a writer destroyed without Finish() (an error while reading) leaves no rawlog and
    /// no times.txt/poses.txt/calib.txt under the final names.
    virtual void Finish() = 0;
};

/// KITTI folder: velodyne/NNNNNN.bin (float32 x y z i), poses.txt (reference poses, if every scan has
/// one), times.txt, calib.txt with identity Tr. Refuses an existing non-empty folder unless `force`.
std::unique_ptr<DatasetWriter> CreateKittiWriter(const std::filesystem::path& folder, bool force = false);

/// MRPT rawlog (observation-only layout, gzip when the name ends in .gz): CObservationPointCloud per scan
/// (or CObservation2DRangeScan), CObservationOdometry for priors, and the reference pose as a
/// CObservationRobotPose labelled "GROUND_TRUTH".
std::unique_ptr<DatasetWriter> CreateRawlogWriter(const std::filesystem::path& file,
                                                  const WriterOptions& options = {}, bool force = false);

/// True for names ending in .rawlog or .rawlog.gz (what CreateWriter and OpenDataset treat as rawlogs).
bool HasRawlogExtension(const std::filesystem::path& path);

/// Picks the writer from the path: a name ending in .rawlog or .rawlog.gz, else a KITTI folder.
std::unique_ptr<DatasetWriter> CreateWriter(const std::filesystem::path& path, const WriterOptions& options = {},
                                            bool force = false);

}  // namespace revisit
