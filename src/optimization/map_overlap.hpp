#pragma once
/// Which local maps the corrected poses lay over each other: the candidates of the proximity pass
/// (docs/method.md, "At the end of the run"). Each map keeps a coarse footprint, the ground cells
/// its points occupy in its own frame; placed by the maps' poses, footprints that share many cells
/// are maps worth registering directly, whether or not their images ever matched.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "core/trajectory.hpp"

namespace revisit {

/// The centres (x, y in the map frame, [m]) of the `cell_size` [m] ground cells that
/// `points_in_map` occupy, each once, in a deterministic order.
std::vector<Eigen::Vector2d> MapFootprint(const std::vector<Eigen::Vector3f>& points_in_map, double cell_size);

struct PredictedOverlap {
    int query = 0;         ///< the later map
    int ref = 0;           ///< an earlier map
    double overlap = 0.0;  ///< shared cells / cells of the smaller footprint [0..1]
};

/// Pairs (query, ref < query) whose footprints, placed by `T_world_map`, share at least `min_overlap`
/// of the smaller one's cells; per query map the `max_per_query` largest overlaps (ties: the earlier
/// reference), pairs `skip` refuses left out. Ordered by query, then overlap, largest first.
/// Cost: one hash insertion per footprint cell plus one count per shared cell.
std::vector<PredictedOverlap> PredictOverlaps(const std::vector<std::vector<Eigen::Vector2d>>& footprints,
                                              const Poses& T_world_map, double cell_size, double min_overlap,
                                              int max_per_query, const std::function<bool(int, int)>& skip);

}  // namespace revisit
