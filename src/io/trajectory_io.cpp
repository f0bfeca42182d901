#include "io/trajectory_io.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/se3.hpp"

namespace revisit {
namespace {

std::ifstream OpenText(const std::filesystem::path& file) {
    if (file.empty()) throw DatasetError(file, "no file name given");
    if (!std::filesystem::is_regular_file(file)) throw DatasetError(file, "no such file");
    std::ifstream in(file);
    if (!in) throw DatasetError(file, "cannot open for reading");
    return in;
}

/// Formats the whole file in memory, then writes it all or nothing (core/atomic_file.hpp).
template <typename Fill>
void WriteText(const std::filesystem::path& file, Fill fill) {
    WriteFileAtomically(file, [&fill](std::ostream& out) {
        out << std::setprecision(9) << std::fixed;
        fill(out);
    });
}

/// Parses all numbers of a line (commas count as spaces when `csv`); false if any token is not a
/// number, or is not finite unless `allow_nan`.
bool ParseNumbers(const std::string& line, std::vector<double>& values, bool csv = false, bool allow_nan = false) {
    values.clear();
    std::string text = line;
    if (csv) std::replace(text.begin(), text.end(), ',', ' ');
    std::istringstream tokens(text);
    std::string token;
    while (tokens >> token) {
        char* end = nullptr;
        const double value = std::strtod(token.c_str(), &end);
        if (end == token.c_str() || *end != '\0' || std::isinf(value) || (std::isnan(value) && !allow_nan)) return false;
        values.push_back(value);
    }
    return true;
}

bool IsBlankOrComment(const std::string& line) {
    const auto first = line.find_first_not_of(" \t\r");
    return first == std::string::npos || line[first] == '#';
}

}  // namespace

void ForEachNumberLine(const std::filesystem::path& file, const NumberLines& format,
                       const std::function<void(const std::vector<double>&, std::size_t)>& on_values) {
    auto in = OpenText(file);
    std::string line;
    std::vector<double> values;
    std::size_t line_number = 0;
    while (std::getline(in, line)) {
        ++line_number;
        if (IsBlankOrComment(line)) continue;
        if (!ParseNumbers(line, values, format.csv, format.skip_nan_lines) || values.size() != format.count) {
            throw DatasetError(file, "malformed " + format.what + " line: expected " + std::to_string(format.count) +
                                         (format.csv ? " comma-separated numbers" : " numbers"),
                               line_number);
        }
        if (format.skip_nan_lines && std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); })) continue;
        on_values(values, line_number);
    }
}

Eigen::Isometry3d CleanPose(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const std::filesystem::path& file,
                            std::size_t line_number) {
    // Text files round rotations to a few digits; a matrix far from a rotation is an error, not noise.
    const Eigen::Matrix3d R_clean = NearestRotation(R);
    if ((R_clean - R).norm() > 1e-2) throw DatasetError(file, "rotation part is not a rotation matrix", line_number);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = R_clean;
    T.translation() = t;
    return T;
}

Eigen::Isometry3d CleanPose(const Eigen::Quaterniond& q, const Eigen::Vector3d& t, const std::filesystem::path& file,
                            std::size_t line_number) {
    if (std::abs(q.norm() - 1.0) > 1e-2) throw DatasetError(file, "quaternion is not unit length", line_number);
    return CleanPose(q.normalized().toRotationMatrix(), t, file, line_number);
}

void AppendStampedPose(Trajectory& trajectory, double t, const Eigen::Isometry3d& T, const std::filesystem::path& file,
                       std::size_t line_number) {
    if (!trajectory.timestamps.empty() && t < trajectory.timestamps.back()) {
        throw DatasetError(file, "time stamps go backwards", line_number);
    }
    trajectory.timestamps.push_back(t);
    trajectory.poses.push_back(T);
}

namespace {

/// A KITTI line as WriteKittiPoses writes it: the 3 x 4 matrix [R | t], row by row (the stream's precision).
void WriteKittiFields(std::ostream& out, const Eigen::Isometry3d& T) {
    const Eigen::Matrix<double, 3, 4> M = T.matrix().topRows<3>();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) out << (r + c == 0 ? "" : " ") << M(r, c);
    }
}

/// The pose of the twelve numbers WriteKittiFields writes.
Eigen::Isometry3d KittiFieldsPose(const double* v, const std::filesystem::path& file, std::size_t line_number) {
    Eigen::Matrix3d R;
    R << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
    return CleanPose(R, Eigen::Vector3d(v[3], v[7], v[11]), file, line_number);
}

}  // namespace

Trajectory ReadKittiPoses(const std::filesystem::path& file) {
    Trajectory trajectory;
    ForEachNumberLine(file, {12, "KITTI pose"}, [&](const std::vector<double>& v, std::size_t line_number) {
        trajectory.poses.push_back(KittiFieldsPose(v.data(), file, line_number));
    });
    return trajectory;
}

namespace {

/// A TUM line's pose fields as WriteTumPoses writes them: x y z qx qy qz qw (the stream's precision).
void WriteTumFields(std::ostream& out, const Eigen::Isometry3d& T) {
    const Eigen::Quaterniond q(T.linear());
    const Eigen::Vector3d t = T.translation();
    out << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << ' ' << q.w();
}

/// The pose of the seven numbers WriteTumFields writes.
Eigen::Isometry3d TumFieldsPose(const double* v, const std::filesystem::path& file, std::size_t line_number) {
    return CleanPose(Eigen::Quaterniond(v[6], v[3], v[4], v[5]), Eigen::Vector3d(v[0], v[1], v[2]), file, line_number);
}

}  // namespace

Trajectory ReadTumPoses(const std::filesystem::path& file) {
    Trajectory trajectory;
    ForEachNumberLine(file, {8, "TUM pose"}, [&](const std::vector<double>& v, std::size_t line_number) {
        AppendStampedPose(trajectory, v[0], TumFieldsPose(v.data() + 1, file, line_number), file, line_number);
    });
    return trajectory;
}

Trajectory ReadSecNsecPoses(const std::filesystem::path& file) {
    Trajectory trajectory;
    ForEachNumberLine(file, {9, "sec,nsec,x,y,z,qx,qy,qz,qw pose", true},
                      [&](const std::vector<double>& v, std::size_t line_number) {
                          if (v[1] < 0.0 || v[1] >= 1e9) throw DatasetError(file, "nsec is not in [0, 1e9)", line_number);
                          const Eigen::Quaterniond q(v[8], v[5], v[6], v[7]);
                          AppendStampedPose(trajectory, v[0] + v[1] * 1e-9,
                                            CleanPose(q, Eigen::Vector3d(v[2], v[3], v[4]), file, line_number), file,
                                            line_number);
                      });
    if (trajectory.empty()) throw DatasetError(file, "no poses");
    return trajectory;
}

Trajectory ReadPoses(const std::filesystem::path& file) {
    auto in = OpenText(file);
    std::string line;
    std::vector<double> values;
    while (std::getline(in, line)) {
        if (IsBlankOrComment(line)) continue;
        ParseNumbers(line, values, line.find(',') != std::string::npos);
        if (line.find(',') != std::string::npos && values.size() == 9) return ReadSecNsecPoses(file);
        if (values.size() == 12) return ReadKittiPoses(file);
        if (values.size() == 8) return ReadTumPoses(file);
        throw DatasetError(file, "not a KITTI (12 numbers per line), TUM (8 numbers per line) or sec,nsec,x,y,z,qx,qy,qz,qw "
                                 "(9 comma-separated numbers) trajectory");
    }
    throw DatasetError(file, "trajectory file has no poses");
}

std::vector<double> ReadTimes(const std::filesystem::path& file) {
    std::vector<double> times;
    ForEachNumberLine(file, {1, "time"}, [&](const std::vector<double>& v, std::size_t line_number) {
        // Every later stage pairs scans by time: a step backwards is damage, named where it is.
        if (!times.empty() && v[0] < times.back()) {
            throw DatasetError(file, "time goes backwards (" + std::to_string(v[0]) + " s after " +
                                         std::to_string(times.back()) + " s)", line_number);
        }
        times.push_back(v[0]);
    });
    return times;
}

void WriteKittiPoses(const std::filesystem::path& file, const Poses& poses) {
    WriteText(file, [&poses](std::ostream& out) {
        for (const auto& T : poses) {
            WriteKittiFields(out, T);
            out << '\n';
        }
    });
}

Eigen::Isometry3d AsStoredKittiPose(const Eigen::Isometry3d& T) {
    std::ostringstream text;
    text << std::setprecision(9) << std::fixed;
    WriteKittiFields(text, T);
    std::vector<double> v;
    ParseNumbers(text.str(), v);
    return KittiFieldsPose(v.data(), "(pose in memory)", 0);
}

Eigen::Isometry3d AsStoredTumPose(const Eigen::Isometry3d& T) {
    std::ostringstream text;
    text << std::setprecision(9) << std::fixed;
    WriteTumFields(text, T);
    std::vector<double> v;
    ParseNumbers(text.str(), v);
    return TumFieldsPose(v.data(), "(pose in memory)", 0);
}

double AsStoredTime(double t) {
    std::ostringstream text;
    text << std::setprecision(9) << std::fixed << t;
    return std::strtod(text.str().c_str(), nullptr);
}

void WriteTumPoses(const std::filesystem::path& file, const Trajectory& trajectory) {
    if (!trajectory.has_timestamps() && !trajectory.empty()) {
        throw DatasetError(file, "TUM output needs one timestamp per pose");
    }
    WriteText(file, [&trajectory](std::ostream& out) {
        for (std::size_t i = 0; i < trajectory.size(); ++i) {
            out << trajectory.timestamps[i] << ' ';
            WriteTumFields(out, trajectory.poses[i]);
            out << '\n';
        }
    });
}

void WriteTimes(const std::filesystem::path& file, const std::vector<double>& timestamps) {
    WriteText(file, [&timestamps](std::ostream& out) {
        for (const double t : timestamps) out << t << '\n';
    });
}

std::vector<long> AssociateByTime(const std::vector<double>& trajectory_times, const std::vector<double>& query_times,
                                  double max_dt) {
    std::vector<long> indices(query_times.size(), -1);
    for (std::size_t q = 0; q < query_times.size(); ++q) {
        const auto it = std::lower_bound(trajectory_times.begin(), trajectory_times.end(), query_times[q]);
        long best = -1;
        double best_dt = max_dt;
        for (auto candidate : {it, it == trajectory_times.begin() ? it : std::prev(it)}) {
            if (candidate == trajectory_times.end()) continue;
            const double dt = std::abs(*candidate - query_times[q]);
            if (dt <= best_dt) {
                best_dt = dt;
                best = static_cast<long>(candidate - trajectory_times.begin());
            }
        }
        indices[q] = best;
    }
    return indices;
}

}  // namespace revisit
