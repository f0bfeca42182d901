#pragma once
/// A local map's points as the run folder keeps them (maps/map_NNNN.rvmap, docs/formats.md): integer
/// coordinates on a grid of 1/50 of the map's voxel, in a canonical order, zstd-compressed, versioned
/// and checksummed. About 2.5 bytes per point instead of the 16 of a KITTI .bin.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace revisit {

/// Grid cells per map voxel along each axis. The maps are already one point per `output.map_voxel`
/// voxel (0.5 m: a 1 cm grid), so snapping moves a point by at most 1/100 of the voxel per axis (5 mm,
/// 2.9 mm RMS), well below the refinement's residuals (a few cm) and its own voxel.
constexpr int kMapPointCellsPerVoxel = 50;

/// [m] the grid step of maps stored at `map_voxel`.
inline double MapPointStep(double map_voxel) { return map_voxel / kMapPointCellsPerVoxel; }

/// The points exactly as they read back from a file written at `step_m`: snapped to the grid and in
/// the file's order (by voxel of the grid's 50-cell blocks, then by cell). The chain keeps these, so a
/// map read back is the map it used. Throws std::invalid_argument for a non-finite or too distant point.
std::vector<Eigen::Vector3f> SnapToMapPointGrid(const std::vector<Eigen::Vector3f>& points, double step_m);

/// The file's bytes for `points` (snapped as SnapToMapPointGrid does).
std::string EncodeMapPoints(const std::vector<Eigen::Vector3f>& points, double step_m);
/// Reads `bytes` back; a damaged, truncated or foreign file is a DatasetError naming `file`.
std::vector<Eigen::Vector3f> DecodeMapPoints(std::string_view bytes, const std::filesystem::path& file);

void SaveMapPoints(const std::filesystem::path& file, const std::vector<Eigen::Vector3f>& points, double step_m);
std::vector<Eigen::Vector3f> LoadMapPoints(const std::filesystem::path& file);

}  // namespace revisit
