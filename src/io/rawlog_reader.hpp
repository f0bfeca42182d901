#pragma once
/// MRPT rawlog reader: both layouts (observation-only and action/sensory-frame), gzip or plain.
#include <memory>

#include "io/reader.hpp"

namespace revisit {

/// Scans come from CObservationPointCloud, CObservationVelodyneScan, CObservation3DRangeScan,
/// CObservation2DRangeScan and CObservationRotatingScan, in the vehicle frame (the observation's
/// sensorPose applied). Priors: CObservationOdometry, CObservationRobotPose and
/// CActionRobotMovement2D/3D; a CObservationRobotPose labelled "GROUND_TRUTH" is the reference pose.
std::unique_ptr<Reader> OpenRawlog(const std::filesystem::path& file, const ReaderOptions& options);

}  // namespace revisit
