#include "io/bag_topics.hpp"

#include "core/error.hpp"
#include "io/ros_messages.hpp"

namespace revisit {
namespace {

std::string Describe(const std::vector<BagTopic>& topics, const std::vector<int>& which) {
    std::string text;
    for (const int i : which) text += (text.empty() ? "" : ", ") + topics[i].name + " (" + RosTypeName(topics[i].type) + ")";
    return text.empty() ? "none" : text;
}

std::vector<int> All(const std::vector<BagTopic>& topics) {
    std::vector<int> all;
    for (int i = 0; i < int(topics.size()); ++i) all.push_back(i);
    return all;
}

/// The topic `name` (which must have one of `kinds`), else the only topic of those kinds, else -1.
int Choose(const std::vector<BagTopic>& topics, const std::string& name, std::vector<TopicKind> named_kinds,
           std::vector<TopicKind> automatic_kinds, int taken, const char* what, const char* option,
           const std::filesystem::path& file, bool required) {
    const auto fits = [&](int i, const std::vector<TopicKind>& kinds) {
        for (const TopicKind kind : kinds) {
            if (KindOf(topics[i]) == kind) return true;
        }
        return false;
    };
    if (name == "none" && !required) return -1;
    if (!name.empty()) {
        for (int i = 0; i < int(topics.size()); ++i) {
            if (topics[i].name != name) continue;
            if (!fits(i, named_kinds)) {
                throw DatasetError(file, std::string(option) + " " + name + " is a " + RosTypeName(topics[i].type) +
                                             " topic, not " + what);
            }
            return i;
        }
        throw DatasetError(file, std::string("no topic ") + name + " (" + option + "); the topics: " + Describe(topics, All(topics)));
    }
    std::vector<int> candidates;
    for (int i = 0; i < int(topics.size()); ++i) {
        if (i != taken && fits(i, automatic_kinds)) candidates.push_back(i);
    }
    if (candidates.size() > 1) {
        throw DatasetError(file, std::string("several topics could be ") + what + ": " + Describe(topics, candidates) +
                                     "; choose one with " + option + (required ? "" : " (or none)"));
    }
    if (candidates.empty() && required) {
        throw DatasetError(file, std::string("no ") + what + " topic; the topics: " + Describe(topics, All(topics)));
    }
    return candidates.empty() ? -1 : candidates.front();
}

}  // namespace

TopicKind KindOf(const BagTopic& topic) {
    const std::string type = RosTypeName(topic.type);
    if (type == "sensor_msgs/PointCloud2") return TopicKind::kPointCloud2;
    if (type == "sensor_msgs/LaserScan") return TopicKind::kLaserScan;
    if (type == "nav_msgs/Odometry") return TopicKind::kOdometry;
    if (type == "geometry_msgs/PoseStamped") return TopicKind::kPoseStamped;
    if (type == "nav_msgs/Path") return TopicKind::kPath;
    if (type == "tf2_msgs/TFMessage") return TopicKind::kTf;
    return TopicKind::kOther;
}

bool IsStaticTf(const BagTopic& topic) {
    const std::string suffix = "tf_static";
    return KindOf(topic) == TopicKind::kTf && topic.name.size() >= suffix.size() &&
           topic.name.compare(topic.name.size() - suffix.size(), suffix.size(), suffix) == 0;
}

TopicChoice ChooseTopics(const std::vector<BagTopic>& topics, const ReaderOptions& options, const std::filesystem::path& file) {
    using K = TopicKind;
    TopicChoice choice;
    choice.points = Choose(topics, options.points_topic, {K::kPointCloud2, K::kLaserScan}, {K::kPointCloud2, K::kLaserScan},
                           -1, "the scans (PointCloud2 or LaserScan)", "--topic / input.topic", file, true);
    choice.reference = Choose(topics, options.reference_topic, {K::kPoseStamped, K::kPath, K::kOdometry},
                              {K::kPoseStamped, K::kPath}, -1, "the reference poses (PoseStamped, Path or Odometry)",
                              "input.reference_topic", file, false);
    choice.odometry = Choose(topics, options.odometry_topic, {K::kOdometry}, {K::kOdometry}, choice.reference,
                             "the odometry prior (Odometry)", "input.odometry_topic", file, false);
    if (choice.odometry >= 0 && choice.odometry == choice.reference) {
        throw DatasetError(file, "topic " + topics[choice.odometry].name + " cannot be both the odometry and the reference");
    }
    return choice;
}

std::vector<TopicSummary> SummarizeTopics(const std::vector<BagTopic>& topics, const TopicChoice& choice) {
    std::vector<TopicSummary> summary;
    for (int i = 0; i < int(topics.size()); ++i) {
        const BagTopic& topic = topics[i];
        TopicSummary s;
        s.name = topic.name;
        s.type = topic.type;
        s.messages = topic.count;
        if (topic.count > 1 && topic.last_ns > topic.first_ns) {
            // The span in double: stamps read from a file can be any int64, and their difference overflow.
            s.rate_hz = double(topic.count - 1) / ((double(topic.last_ns) - double(topic.first_ns)) * 1e-9);
        }
        s.role = i == choice.points      ? "points"
                 : i == choice.odometry  ? "odometry"
                 : i == choice.reference ? "reference"
                 : IsStaticTf(topic)     ? "static transforms"
                                         : "unused";
        summary.push_back(std::move(s));
    }
    return summary;
}

}  // namespace revisit
