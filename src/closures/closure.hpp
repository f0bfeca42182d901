#pragma once
/// A detected loop closure between two local maps: everything the pipeline and the report need.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace revisit {

struct ScanRange {
    std::size_t first = 0;
    std::size_t last = 0;  ///< inclusive
};

/// A descriptor match between a query keypoint and a reference keypoint.
struct FeatureMatch {
    std::int32_t query_keypoint = 0;
    std::int32_t ref_keypoint = 0;
    std::int32_t distance = 0;  ///< [bits]
};

struct Closure {
    int query_id = 0;  ///< LocalMap::id of the new map
    int ref_id = 0;    ///< LocalMap::id of the earlier map
    int query_session = 0;
    int ref_session = 0;
    ScanRange query_scans;
    ScanRange ref_scans;
    /// Maps points of the reference map frame into the query map frame (METHOD.md section 5):
    /// T = T_ground_query^-1 * T_2d * T_ground_ref.
    Eigen::Matrix4d T_query_ref = Eigen::Matrix4d::Identity();
    int num_inliers = 0;
    int num_votes = 0;                       ///< tree matches that voted for the reference map
    std::vector<FeatureMatch> matches;       ///< all matches with the reference map
    std::vector<std::uint8_t> inlier_mask;   ///< one flag per match
    std::vector<Eigen::Vector2f> query_keypoints;  ///< [pixels] in the query density image
    std::vector<Eigen::Vector2f> ref_keypoints;    ///< [pixels] in the reference density image
};

}  // namespace revisit
