#include "io/carmen_reader.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

#include "core/error.hpp"
#include "core/se3.hpp"
#include "io/carmen_line.hpp"
#include "io/compressed_text.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

constexpr std::size_t kMaxLineBytes = 1 << 20;  ///< a 1081-beam ROBOTLASER1 line is ~20 kB
constexpr double kNominalPeriod = 0.1;          ///< [s] between scans of a log without times
constexpr double kMinRange = 0.05;              ///< [m] readings at or below: no return (0 is CARMEN's "none")
constexpr double kMaxRangeMargin = 1e-3;        ///< [m] readings this close to the maximum range: no return

Eigen::Isometry3d ToIsometry(const Pose2& p) { return PoseFromXYZRPY(p.x, p.y, 0.0, 0.0, 0.0, p.theta); }

/// What the first pass found.
struct LogSummary {
    std::string kind;               ///< the laser read
    std::size_t scans = 0;
    double max_reading = 0.0;       ///< [m] the largest range of that laser: FLASER's "max range" value
    bool has_times = false;         ///< that laser's times are positive and increase from line to line
    std::map<std::string, std::size_t> other_lasers;
    std::map<std::string, std::size_t> other_messages;
};

class CarmenReader final : public Reader {
  public:
    CarmenReader(const fs::path& path, const ReaderOptions& options, LogSummary summary)
        : path_(path), options_(options), summary_(std::move(summary)), lines_(path, kMaxLineBytes) {
        info_.format = "carmen";
        info_.path = path;
        info_.num_scans = summary_.scans;
        if (!summary_.has_times) {
            info_.timing = "the log's time stamps do not increase (all 0 or all the same): scans stamped every " +
                           std::to_string(kNominalPeriod).substr(0, 3) + " s (nominal)";
        }
        stats_.skipped_sensors = summary_.other_lasers;
        stats_.skipped_classes = summary_.other_messages;
    }

    std::optional<Scan> Next() override {
        std::string line, name;
        CarmenLaser laser;
        CarmenOdom odom;
        while (lines_.Next(line)) {
            if (ParseCarmenLine(line, name, laser, odom) != CarmenLineKind::kLaser || laser.kind != summary_.kind) continue;
            return MakeScan(laser);
        }
        return std::nullopt;
    }

    const DatasetInfo& Info() const override { return info_; }

  private:
    Scan MakeScan(const CarmenLaser& laser) {
        Scan scan;
        scan.index = next_index_++;
        scan.timestamp = summary_.has_times ? laser.timestamp : kNominalPeriod * static_cast<double>(scan.index);
        scan.sensor_label = laser.kind;
        const std::size_t n = laser.ranges.size();
        const double max_range = laser.stated_geometry ? laser.max_range : summary_.max_reading;
        PlanarBeams beams;
        beams.ranges.assign(n, 0.f);
        beams.stated_aperture = laser.stated_geometry ? laser.fov : M_PI;
        beams.aperture = options_.laser_aperture > 0.0 ? options_.laser_aperture : beams.stated_aperture;
        beams.T_vehicle_sensor = ToIsometry(laser.robot).inverse() * ToIsometry(laser.laser);
        const double step = n > 1 ? beams.aperture / static_cast<double>(n - 1) : 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            const double r = laser.ranges[i];
            if (!(r > kMinRange) || !(r < max_range - kMaxRangeMargin)) continue;
            double angle;
            if (options_.laser_aperture > 0.0) {
                angle = -beams.aperture / 2.0 + step * static_cast<double>(i);
            } else if (laser.stated_geometry) {
                angle = laser.start_angle + laser.resolution * static_cast<double>(i);
            } else {
                // CARMEN's FLASER: beam i at -90 deg + i * 180 / (n - 1) deg, counter-clockwise.
                const double degrees = n > 1 ? -90.0 + static_cast<double>(i) * 180.0 / static_cast<double>(n - 1) : 0.0;
                angle = degrees * (M_PI / 180.0);
            }
            beams.ranges[i] = static_cast<float>(r);
            scan.points.emplace_back(static_cast<float>(r * std::cos(angle)), static_cast<float>(r * std::sin(angle)), 0.f);
        }
        scan.planar_beams = std::move(beams);
        scan.T_odom_sensor = ToIsometry(laser.laser);
        stats_.scans++;
        stats_.points += scan.points.size();
        return scan;
    }

    fs::path path_;
    ReaderOptions options_;
    LogSummary summary_;
    CompressedTextLines lines_;
    DatasetInfo info_;
    std::size_t next_index_ = 0;
};

LogSummary Summarize(const fs::path& path, const ReaderOptions& options) {
    CompressedTextLines lines(path, kMaxLineBytes);
    LogSummary summary;
    summary.kind = options.sensor_label;
    if (!summary.kind.empty() && summary.kind != "FLASER" && summary.kind != "RLASER" && summary.kind != "ROBOTLASER1") {
        throw DatasetError(path, "input.sensor_label '" + summary.kind + "': a CARMEN log's lasers are FLASER, RLASER or ROBOTLASER1");
    }
    std::map<std::string, std::size_t> lasers;
    std::map<std::string, double> max_reading;
    std::map<std::string, bool> times_increase;  // positive and strictly increasing so far
    std::map<std::string, double> last_time;
    std::string line, name;
    CarmenLaser laser;
    CarmenOdom odom;
    bool recognized = false;
    while (lines.Next(line)) {
        CarmenLineKind kind;
        try {
            kind = ParseCarmenLine(line, name, laser, odom);
        } catch (const std::invalid_argument& e) {
            throw DatasetError(path, e.what(), lines.line_number());
        }
        if (kind == CarmenLineKind::kBlank) continue;
        if (!recognized) {
            // The first message says whether this is a CARMEN log at all.
            if (!IsCarmenMessageName(name)) {
                throw DatasetError(path, "not a CARMEN log: the first line starts with '" + name.substr(0, 40) +
                                             "' (expected PARAM, ODOM, FLASER, ROBOTLASER1, ...)",
                                   lines.line_number());
            }
            recognized = true;
        }
        if (kind == CarmenLineKind::kLaser) {
            ++lasers[laser.kind];
            if (summary.kind.empty()) summary.kind = laser.kind;
            double& m = max_reading[laser.kind];
            for (const double r : laser.ranges) m = std::max(m, r);
            const bool first = times_increase.count(laser.kind) == 0;
            bool& increase = times_increase[laser.kind];
            increase = laser.timestamp > 0.0 && (first || (increase && laser.timestamp > last_time[laser.kind]));
            last_time[laser.kind] = laser.timestamp;
        } else if (kind == CarmenLineKind::kOther) {
            ++summary.other_messages[name.substr(0, 40)];
        }
    }
    if (!recognized) throw DatasetError(path, "empty: no CARMEN messages");
    if (lasers.count(summary.kind) == 0) {
        throw DatasetError(path, summary.kind.empty() ? std::string("no laser lines (FLASER, RLASER or ROBOTLASER1)")
                                                      : "no " + summary.kind + " lines (input.sensor_label)");
    }
    summary.scans = lasers[summary.kind];
    summary.max_reading = max_reading[summary.kind];
    summary.has_times = times_increase[summary.kind];
    for (const auto& [kind, count] : lasers) {
        if (kind != summary.kind) summary.other_lasers[kind] = count;
    }
    return summary;
}

bool EndsWith(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

bool HasCarmenExtension(const fs::path& path) {
    const std::string name = path.filename().string();
    for (const char* base : {".log", ".clf"}) {
        for (const char* compression : {"", ".gz", ".bz2"}) {
            if (EndsWith(name, std::string(base) + compression)) return true;
        }
    }
    return false;
}

std::unique_ptr<Reader> OpenCarmenLog(const fs::path& path, const ReaderOptions& options) {
    if (!options.poses_file.empty()) {
        throw DatasetError(options.poses_file, "a CARMEN log's reference poses come with --gt FILE (paired by time stamp or index)");
    }
    return std::make_unique<CarmenReader>(path, options, Summarize(path, options));
}

}  // namespace revisit
