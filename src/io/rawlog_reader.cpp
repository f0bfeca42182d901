#include "io/rawlog_reader.hpp"

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
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <deque>
#include <sstream>
#include <limits>

#include "core/error.hpp"
#include "io/allocation_budget.hpp"
#include "io/rawlog_scan.hpp"
#include "io/rawlog_stream.hpp"

namespace revisit {
namespace {

class RawlogReader final : public Reader {
  public:
    RawlogReader(const std::filesystem::path& file, const ReaderOptions& options)
        : file_(file), options_(options), label_filter_(options.sensor_label), stream_(file) {
        info_.format = "rawlog";
        info_.path = file;
    }

    std::optional<Scan> Next() override {
        while (pending_.empty()) {
            if (done_) return std::nullopt;
            try {
                if (!ReadEntry()) return std::nullopt;
            } catch (const DatasetError& e) {
                if (!options_.allow_truncated) throw;
                // --allow-truncated: keep what was read, and say so.
                done_ = true;
                info_.truncated = e.what();
                pending_.clear();  // an entry cut in the middle gives no scan
            }
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
    /// Reads one rawlog object (an action collection, a sensory frame or an observation) into
    /// pending_; false at the clean end of the file. Damage throws DatasetError saying where reading
    /// stopped and how many scans were read.
    bool ReadEntry() {
        mrpt::serialization::CSerializable::Ptr object;
        try {
            if (stream_.AtEnd()) return false;
            // What one object may allocate is bounded by what the rest of the file can hold: MRPT
            // allocates what a size field says before it reads the data (AllocationBudget).
            const std::uint64_t left = stream_.MaxBytesLeft();
            const AllocationBudget budget(static_cast<std::size_t>(
                std::min<std::uint64_t>(2 * left + kAllocationSlack, std::numeric_limits<std::size_t>::max() / 2)));
            object_start_ = stream_.getPosition();
            object = archive_.ReadObject();
        } catch (const DatasetError& e) {
            Stop(stream_.error().empty() ? e.what() : stream_.error());  // gzip, CRC or read error
        } catch (const std::bad_alloc&) {
            Stop("an object declares more data than the rest of the file holds");
        } catch (const std::exception& e) {
            Stop(stream_.error().empty() ? "corrupt object: " + MrptMessage(e.what()) : stream_.error());
        }
        if (const auto actions = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(object)) {
            for (const auto& action : *actions) HandleAction(*action);
        } else if (const auto frame = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(object)) {
            for (const auto& obs : *frame) HandleObservation(obs);
        } else if (const auto observation = std::dynamic_pointer_cast<mrpt::obs::CObservation>(object)) {
            HandleObservation(observation);
        } else if (object) {
            stats_.skipped_classes[object->GetRuntimeClass()->className]++;
        }
        ++entry_;
        return true;
    }

    /// Where object entry_ starts: its own byte offset (in the decompressed data for gzip), not the
    /// read buffer's position.
    std::string ObjectStart() const {
        return "object " + std::to_string(entry_) + " (starts at " + (stream_.is_gzip() ? "decompressed byte " : "byte ") +
               std::to_string(object_start_) + " of " + std::to_string(stream_.getTotalBytesCount()) +
               (stream_.is_gzip() ? " compressed" : "") + ")";
    }

    [[noreturn]] void Stop(const std::string& problem) const {
        const std::string read_up_to =
            stream_.is_gzip() ? "; the damage is before compressed byte " + std::to_string(stream_.file_position()) : std::string();
        throw DatasetError(file_, "damaged rawlog: " + problem + "; reading stopped in " + ObjectStart() + read_up_to +
                                      " after " + std::to_string(stats_.scans + pending_.size()) + " scans");
    }

    /// MRPT nests exceptions, each with a banner and a backtrace: the innermost message says what went
    /// wrong, the outermost typed object where.
    static std::string MrptMessage(const std::string& text) {
        std::istringstream lines(text);
        std::string line, message, object;
        const std::string kPrefix = "Message:", kParsing = "Exception while parsing typed object '";
        while (std::getline(lines, line)) {
            if (line.rfind(kPrefix, 0) != 0) continue;
            message = line.substr(line.find_first_not_of(' ', kPrefix.size()));
            if (object.empty() && message.rfind(kParsing, 0) == 0) {
                object = message.substr(kParsing.size(), message.find('\'', kParsing.size()) - kParsing.size());
            }
        }
        if (message.empty()) message = text.substr(0, text.find('\n'));
        return object.empty() ? message : message + " (in " + object + ")";
    }

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
        // Every later stage pairs scans by time (and the run folder's TUM files require it): a step
        // backwards, e.g. two recordings concatenated, is named here, where it is.
        if (last_time_ && scan->timestamp < *last_time_) {
            std::ostringstream problem;
            problem.precision(17);
            problem << "time goes backwards in " << ObjectStart() << ": scan " << stats_.scans + pending_.size() << " at "
                    << scan->timestamp << " s after " << *last_time_ << " s (two recordings concatenated?); "
                    << "--allow-truncated keeps the scans before it";
            throw DatasetError(file_, problem.str());
        }
        last_time_ = scan->timestamp;
        scan->T_odom_sensor = T_odom_;
        scan->T_world_sensor = T_reference_;
        T_reference_.reset();  // a ground-truth pose belongs to the scan right after it
        pending_.push_back(std::move(*scan));
    }

    std::filesystem::path file_;
    ReaderOptions options_;
    std::string label_filter_;
    DatasetInfo info_;
    static constexpr std::uint64_t kAllocationSlack = 256ull << 20;  ///< [bytes] beyond 2x the data left
    RawlogInputStream stream_;
    mrpt::serialization::CArchiveStreamBase<RawlogInputStream> archive_{stream_};
    bool done_ = false;
    std::size_t entry_ = 0;            ///< objects read so far; Stop names the one being read
    std::uint64_t object_start_ = 0;   ///< [bytes] where the object being read starts
    std::optional<double> last_time_;  ///< [s] of the last scan kept
    std::optional<Eigen::Isometry3d> T_odom_;
    std::optional<Eigen::Isometry3d> T_reference_;
    std::deque<Scan> pending_;
};

}  // namespace

std::unique_ptr<Reader> OpenRawlog(const std::filesystem::path& file, const ReaderOptions& options) {
    return std::make_unique<RawlogReader>(file, options);
}

}  // namespace revisit
