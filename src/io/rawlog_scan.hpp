#pragma once
/// Conversions between MRPT observations and revisit scans (io and apps only: MRPT stays at the edges).
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose3D.h>

#include <optional>

#include "core/scan.hpp"
#include "io/reader.hpp"

namespace revisit {

Eigen::Isometry3d ToIsometry(const mrpt::poses::CPose3D& pose);
mrpt::poses::CPose3D ToCPose3D(const Eigen::Isometry3d& T);

/// The points of a range observation in the vehicle frame (sensorPose applied), with intensities and
/// per-point times where the class has them; nullopt for classes that carry no range data.
/// Non-finite points are dropped and counted in `stats`.
std::optional<Scan> ScanFromObservation(const mrpt::obs::CObservation& obs, ReadStats& stats,
                                        const ReaderOptions& options = {});

}  // namespace revisit
