#pragma once
/// CObservationRotatingScan to points. MRPT 2.5.8 cannot insert this class into a points map, and
/// the class stores no per-row elevation: rows are the sensor's lasers in firing order, so the
/// elevations come from the model's datasheet (VLP-16, or one planar row for 2D scanners).
#include <mrpt/obs/CObservationRotatingScan.h>

#include <optional>
#include <vector>

#include "core/scan.hpp"
#include "io/reader.hpp"

namespace revisit {

/// Elevation per row [rad] for a model and row count, or nullopt when the model is unknown.
std::optional<std::vector<double>> RotatingScanElevations(const std::string& lidar_model, int row_count);

/// Points in the sensor frame with intensities and per-point times, or nullopt for an unknown model
/// (counted by the caller as a skipped class).
std::optional<Scan> RotatingScanPoints(const mrpt::obs::CObservationRotatingScan& obs, ReadStats& stats);

}  // namespace revisit
