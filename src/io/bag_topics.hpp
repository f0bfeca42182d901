#pragma once
/// Which topic of a recording gives the scans, the odometry prior and the reference poses.
#include <filesystem>
#include <string>
#include <vector>

#include "io/bag_source.hpp"

namespace revisit {

enum class TopicKind { kPointCloud2, kLaserScan, kOdometry, kPoseStamped, kPath, kTf, kOther };
TopicKind KindOf(const BagTopic& topic);
/// A TFMessage topic named .../tf_static: its transforms are the static frames.
bool IsStaticTf(const BagTopic& topic);

struct TopicChoice {
    int points = -1, odometry = -1, reference = -1;  ///< indices into the topics, -1: none
};

/// The named topics, else the only one of a fitting type: points = PointCloud2 or LaserScan, odometry =
/// Odometry, reference = PoseStamped or Path (an Odometry topic only when named). "none" chooses none.
/// Throws DatasetError naming the candidates and the option to set when several fit, or a named topic
/// is absent or of another type, or no points topic exists.
TopicChoice ChooseTopics(const std::vector<BagTopic>& topics, const ReaderOptions& options, const std::filesystem::path& file);

/// Every topic with its type, count, rate and role.
std::vector<TopicSummary> SummarizeTopics(const std::vector<BagTopic>& topics, const TopicChoice& choice);

}  // namespace revisit
