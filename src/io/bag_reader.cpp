/// The ROS bag reader over any BagSource: a first pass collects the pose topics (small), the second
/// streams the scans and pairs each with the poses by its stamp.
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "io/bag_poses.hpp"
#include "io/bag_source.hpp"
#include "io/bag_topics.hpp"
#include "io/point_cloud2.hpp"
#include "io/trajectory_io.hpp"

namespace revisit {
namespace {

bool IsPoseKind(TopicKind kind) {
    return kind == TopicKind::kOdometry || kind == TopicKind::kPoseStamped || kind == TopicKind::kPath ||
           kind == TopicKind::kTf;
}

class BagReader final : public Reader {
  public:
    BagReader(std::unique_ptr<BagSource> source, const std::filesystem::path& path, const ReaderOptions& options)
        : source_(std::move(source)), path_(path), options_(options) {
        info_.format = source_->Format();
        info_.path = path;
        ReadPoses();
        const auto& topics = source_->Topics();
        choice_ = ChooseTopics(topics, options_, path_);
        info_.topics = SummarizeTopics(topics, choice_);
        info_.num_scans = topics[choice_.points].count;
        laser_ = KindOf(topics[choice_.points]) == TopicKind::kLaserScan;
        if (choice_.odometry >= 0) odometry_ = series_[choice_.odometry];
        if (choice_.reference >= 0) reference_ = series_[choice_.reference];
        series_.clear();
        odometry_.Sort();
        reference_.Sort();
        if (!options_.poses_file.empty()) UsePosesFile();
        info_.has_reference_poses = !reference_.empty() || !indexed_reference_.empty();
        const std::size_t points = std::size_t(choice_.points);
        source_->Start([points](std::size_t topic) { return topic == points; });
    }

    std::optional<Scan> Next() override {
        if (done_) return std::nullopt;
        BagMessage message;
        try {
            if (!source_->Next(message)) {
                done_ = true;
                return std::nullopt;
            }
        } catch (const DatasetError& e) {
            if (!options_.allow_truncated) throw;
            done_ = true;  // the first pass stopped at the same place: info_.truncated says where
            if (info_.truncated.empty()) info_.truncated = e.what();
            return std::nullopt;
        }
        Scan scan = Decode(message);
        scan.index = stats_.scans++;
        stats_.points += scan.points.size();
        if (scan.stamp_ns == 0) scan.stamp_ns = message.log_time_ns;  // no header stamp: the receive time
        scan.timestamp = double(scan.stamp_ns) * 1e-9;
        if (scan.sensor_label.empty()) scan.sensor_label = source_->Topics()[message.topic].name;
        if (const auto prior = odometry_.Prior(scan.stamp_ns)) scan.T_odom_sensor = prior->T * ChildToSensor(*prior, scan);
        const std::int64_t tolerance = std::llround(options_.reference_tolerance * 1e9);
        if (!indexed_reference_.empty()) {
            if (scan.index < indexed_reference_.size()) scan.T_world_sensor = indexed_reference_[scan.index];
        } else if (const auto reference = reference_.Reference(scan.stamp_ns, tolerance)) {
            scan.T_world_sensor = reference->T * ChildToSensor(*reference, scan);
        }
        return scan;
    }

    const DatasetInfo& Info() const override { return info_; }

  private:
    [[noreturn]] void Fail(const BagMessage& message, std::size_t index, const std::string& problem) const {
        throw DatasetError(path_, "topic " + source_->Topics()[message.topic].name + " message " + std::to_string(index) +
                                      " (" + source_->Where(message) + "): " + problem);
    }

    /// First pass: every pose-like topic's poses (the choice needs the whole topic list first).
    void ReadPoses() {
        source_->Start([this](std::size_t topic) { return IsPoseKind(KindOf(source_->Topics()[topic])); });
        BagMessage m;
        std::map<std::size_t, std::size_t> index;
        while (true) {
            try {
                if (!source_->Next(m)) break;
            } catch (const DatasetError& e) {
                // A damaged or cut container: with allow_truncated the messages before the damage count.
                if (!options_.allow_truncated) throw;
                info_.truncated = e.what();
                break;
            }
            const BagTopic& topic = source_->Topics()[m.topic];
            const std::size_t i = index[m.topic]++;
            try {
                switch (KindOf(topic)) {
                    case TopicKind::kOdometry: series_[m.topic].Add(DecodeOdometry(m.data, m.size, topic.wire)); break;
                    case TopicKind::kPoseStamped: series_[m.topic].Add(DecodePoseStamped(m.data, m.size, topic.wire)); break;
                    case TopicKind::kPath: {
                        // A path topic republishes the whole path: the last message holds it all.
                        PoseSeries& series = series_[m.topic];
                        series.Clear();
                        for (const auto& pose : DecodePath(m.data, m.size, topic.wire)) series.Add(pose);
                        break;
                    }
                    case TopicKind::kTf:
                        if (IsStaticTf(topic)) {
                            for (const auto& transform : DecodeTfMessage(m.data, m.size, topic.wire)) frames_.Add(transform);
                        }
                        break;
                    default: break;
                }
            } catch (const WireError& e) {
                Fail(m, i, e.what());  // a damaged message is never a cut file
            }
        }
    }

    void UsePosesFile() {
        Trajectory trajectory = revisit::ReadPoses(options_.poses_file);
        info_.poses_file = options_.poses_file;
        reference_.Clear();
        if (!trajectory.has_timestamps()) {
            if (trajectory.size() != *info_.num_scans) {
                throw DatasetError(options_.poses_file, std::to_string(trajectory.size()) + " poses without times for " +
                                                            std::to_string(*info_.num_scans) + " scans");
            }
            indexed_reference_ = std::move(trajectory.poses);
            return;
        }
        for (std::size_t i = 0; i < trajectory.size(); ++i) {
            PoseMsg pose;
            pose.stamp_ns = std::llround(trajectory.timestamps[i] * 1e9);
            pose.T = trajectory.poses[i];
            reference_.Add(pose);
        }
        reference_.Sort();
    }

    Scan Decode(const BagMessage& message) {
        const BagTopic& topic = source_->Topics()[message.topic];
        const std::size_t index = scan_messages_++;
        try {
            if (laser_) {
                const LaserScanMsg msg = DecodeLaserScan(message.data, message.size, topic.wire);
                Scan scan = ScanFromLaserScan(msg, options_.laser_aperture, stats_.non_finite_points);
                scan.stamp_ns = msg.stamp_ns;
                scan.sensor_label = msg.frame_id;
                return scan;
            }
            const PointCloud2Msg msg = DecodePointCloud2(message.data, message.size, topic.wire);
            CloudData cloud = PointsFromCloud2(msg);
            Scan scan;
            scan.stamp_ns = msg.stamp_ns;
            scan.sensor_label = msg.frame_id;
            scan.points = std::move(cloud.points);
            scan.intensities = std::move(cloud.intensities);
            scan.point_times = std::move(cloud.point_times);
            stats_.non_finite_points += cloud.non_finite;
            return scan;
        } catch (const WireError& e) {
            Fail(message, index, e.what());
        }
    }

    /// T_child_sensor from the static transforms when the pose's child frame is not the scan's frame
    /// (identity when they agree, when either is unnamed, or when no static transform joins them).
    Eigen::Isometry3d ChildToSensor(const PoseMsg& pose, const Scan& scan) {
        if (pose.child_frame_id.empty() || pose.child_frame_id == scan.sensor_label || frames_.empty()) {
            return Eigen::Isometry3d::Identity();
        }
        const std::string key = pose.child_frame_id + '\n' + scan.sensor_label;
        auto found = child_to_sensor_.find(key);
        if (found == child_to_sensor_.end()) {
            found = child_to_sensor_.emplace(key, frames_.Find(pose.child_frame_id, scan.sensor_label)
                                                      .value_or(Eigen::Isometry3d::Identity())).first;
        }
        return found->second;
    }

    std::unique_ptr<BagSource> source_;
    std::filesystem::path path_;
    ReaderOptions options_;
    DatasetInfo info_;
    TopicChoice choice_;
    bool laser_ = false;
    bool done_ = false;
    std::size_t scan_messages_ = 0;
    std::map<std::size_t, PoseSeries> series_;
    PoseSeries odometry_, reference_;
    Poses indexed_reference_;
    StaticFrames frames_;
    std::map<std::string, Eigen::Isometry3d> child_to_sensor_;
};

}  // namespace

std::unique_ptr<Reader> OpenBag(std::unique_ptr<BagSource> source, const std::filesystem::path& path,
                                const ReaderOptions& options) {
    return std::make_unique<BagReader>(std::move(source), path, options);
}

}  // namespace revisit
