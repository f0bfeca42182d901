#include "io/rawlog_reader.hpp"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CActionRobotMovement3D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <deque>

#include "core/error.hpp"
#include "io/rawlog_scan.hpp"

namespace revisit {
namespace {

class RawlogReader final : public Reader {
  public:
    RawlogReader(const std::filesystem::path& file, const ReaderOptions& options)
        : file_(file), options_(options), label_filter_(options.sensor_label) {
        info_.format = "rawlog";
        info_.path = file;
        if (!stream_.open(file.string())) throw DatasetError(file, "cannot open rawlog");
    }

    std::optional<Scan> Next() override {
        while (pending_.empty()) {
            if (!ReadEntry()) return std::nullopt;
        }
        Scan scan = std::move(pending_.front());
        pending_.pop_front();
        scan.index = stats_.scans++;
        stats_.points += scan.points.size();
        info_.has_reference_poses = info_.has_reference_poses || scan.T_world_sensor.has_value();
        return scan;
    }

    const DatasetInfo& Info() const override { return info_; }

  private:
    /// Reads one rawlog entry into pending_; false at the end of the file.
    bool ReadEntry() {
        mrpt::obs::CActionCollection::Ptr actions;
        mrpt::obs::CSensoryFrame::Ptr frame;
        mrpt::obs::CObservation::Ptr observation;
        bool ok = false;
        try {
            ok = mrpt::obs::CRawlog::getActionObservationPairOrObservation(archive_, actions, frame, observation,
                                                                           entry_);
        } catch (const std::exception& e) {
            throw DatasetError(file_, "corrupt rawlog after entry " + std::to_string(entry_) + ": " +
                                          FirstLine(e.what()));
        }
        if (!ok) {
            // MRPT reports both the end of the file and a decoding failure as false; a gzip stream that
            // stops before its end marker, or trailing garbage, shows up as unread bytes.
            if (stream_.getPosition() < stream_.getTotalBytesCount() && entry_ == 0) {
                throw DatasetError(file_, "not a readable MRPT rawlog");
            }
            return false;
        }
        if (actions) {
            for (const auto& action : *actions) HandleAction(*action);
        }
        if (frame) {
            for (const auto& obs : *frame) HandleObservation(obs);
        }
        if (observation) HandleObservation(observation);
        return true;
    }

    static std::string FirstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

    void HandleAction(const mrpt::obs::CAction& action) {
        if (const auto* m2 = dynamic_cast<const mrpt::obs::CActionRobotMovement2D*>(&action)) {
            mrpt::poses::CPose2D delta;
            m2->poseChange->getMean(delta);
            AccumulateOdometry(ToIsometry(mrpt::poses::CPose3D(delta)));
        } else if (const auto* m3 = dynamic_cast<const mrpt::obs::CActionRobotMovement3D*>(&action)) {
            AccumulateOdometry(ToIsometry(m3->poseChange.mean));
        } else {
            stats_.skipped_classes[action.GetRuntimeClass()->className]++;
        }
    }

    void AccumulateOdometry(const Eigen::Isometry3d& delta) { T_odom_ = T_odom_.value_or(Eigen::Isometry3d::Identity()) * delta; }

    void HandleObservation(const mrpt::obs::CObservation::Ptr& obs) {
        using namespace mrpt::obs;
        if (const auto odo = std::dynamic_pointer_cast<CObservationOdometry>(obs)) {
            T_odom_ = ToIsometry(mrpt::poses::CPose3D(odo->odometry));
            return;
        }
        if (const auto pose = std::dynamic_pointer_cast<CObservationRobotPose>(obs)) {
            (pose->sensorLabel == "GROUND_TRUTH" ? T_reference_ : T_odom_) = ToIsometry(pose->pose.mean);
            return;
        }
        auto scan = ScanFromObservation(*obs, stats_, options_);
        if (!scan) {
            stats_.skipped_classes[obs->GetRuntimeClass()->className]++;
            return;
        }
        if (!label_filter_.empty() && obs->sensorLabel != label_filter_) {
            stats_.skipped_sensors[obs->sensorLabel]++;
            return;
        }
        scan->T_odom_sensor = T_odom_;
        scan->T_world_sensor = T_reference_;
        T_reference_.reset();  // a ground-truth pose belongs to the scan right after it
        pending_.push_back(std::move(*scan));
    }

    std::filesystem::path file_;
    ReaderOptions options_;
    std::string label_filter_;
    DatasetInfo info_;
    mrpt::io::CFileGZInputStream stream_;
    mrpt::serialization::CArchiveStreamBase<mrpt::io::CFileGZInputStream> archive_{stream_};
    std::size_t entry_ = 0;
    std::optional<Eigen::Isometry3d> T_odom_;
    std::optional<Eigen::Isometry3d> T_reference_;
    std::deque<Scan> pending_;
};

}  // namespace

std::unique_ptr<Reader> OpenRawlog(const std::filesystem::path& file, const ReaderOptions& options) {
    return std::make_unique<RawlogReader>(file, options);
}

}  // namespace revisit
