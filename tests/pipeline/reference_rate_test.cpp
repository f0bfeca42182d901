/// A TUM reference at another rate than the scans pairs by time stamp: the shared Livox walk's
/// APE against a reference at 5x and at 0.5x the scan rate is the APE against its per-scan one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "core/pose_interpolation.hpp"
#include "evaluation/trajectory_metrics.hpp"
#include "io/trajectory_io.hpp"
#include "pipeline/pose_file_source.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

void WriteTum(const std::filesystem::path& file, const Trajectory& t) {
    std::ofstream out(file);
    for (std::size_t i = 0; i < t.size(); ++i) {
        const Eigen::Quaterniond q(t.poses[i].linear());
        const Eigen::Vector3d p = t.poses[i].translation();
        char line[256];
        std::snprintf(line, sizeof line, "%.9f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", t.timestamps[i], p.x(), p.y(), p.z(), q.x(),
                      q.y(), q.z(), q.w());
        out << line;
    }
}

struct Walk {
    std::vector<double> times;
    Poses reference;  ///< per scan
    Poses estimate;   ///< the walk's original odometry, per scan
};

struct Paired {
    double ape = 0.0;            ///< [m] RMSE of the walk's odometry against the paired reference
    std::size_t scans = 0;       ///< scans with a reference pose
    double max_exact_error = 0;  ///< [m] at scans whose stamp is one of the file's: paired pose vs the per-scan one
    double interpolation_rms = 0;  ///< [m] paired reference vs the per-scan one, over the paired scans
};

/// The walk's odometry against `file`, paired the way `--gt` pairs it.
Paired PairAgainst(const Walk& walk, const std::filesystem::path& file, const std::vector<bool>& stamp_in_file) {
    const PoseFileSource source(file, "--gt", {});
    Poses estimate, reference;
    Paired result;
    double sum = 0.0;
    for (std::size_t i = 0; i < walk.times.size(); ++i) {
        if (const auto pose = source.At(i, walk.times[i])) {
            estimate.push_back(walk.estimate[i]);
            reference.push_back(*pose);
            const double error = (pose->translation() - walk.reference[i].translation()).norm();
            sum += error * error;
            if (stamp_in_file[i]) result.max_exact_error = std::max(result.max_exact_error, error);
        }
    }
    result.scans = reference.size();
    result.interpolation_rms = std::sqrt(sum / static_cast<double>(reference.size()));
    result.ape = ComputeApe(estimate, reference, true).errors.translation_stats.rmse;
    return result;
}

TEST(ReferenceRate, LivoxWalkApeAtFiveAndHalfTheScanRate) {
    const auto dataset = test::SharedData("livox_handheld_walk");
    REVISIT_REQUIRE_DATA(dataset);
    Walk walk{ReadTimes(dataset / "times.txt"), ReadKittiPoses(dataset / "poses.txt").poses,
              ReadKittiPoses(dataset / "orig_odom_poses.txt").poses};
    ASSERT_EQ(walk.times.size(), walk.reference.size());
    const double per_scan = ComputeApe(walk.estimate, walk.reference, true).errors.translation_stats.rmse;
    ASSERT_GT(per_scan, 0.02);  // the odometry is off the reference: the comparison means something

    test::TempDir dir;
    Trajectory fast, slow;  // 5x: four interpolated poses between each two scans; 0.5x: every second scan's
    for (std::size_t i = 0; i < walk.times.size(); ++i) {
        if (i % 2 == 0) slow.timestamps.push_back(walk.times[i]), slow.poses.push_back(walk.reference[i]);
        for (int k = 0; k < 5 && (k == 0 || i + 1 < walk.times.size()); ++k) {
            const double s = k / 5.0;
            fast.timestamps.push_back(k == 0 ? walk.times[i] : walk.times[i] + s * (walk.times[i + 1] - walk.times[i]));
            fast.poses.push_back(k == 0 ? walk.reference[i] : InterpolatePose(walk.reference[i], walk.reference[i + 1], s));
        }
    }
    WriteTum(dir / "fast.tum", fast);
    WriteTum(dir / "slow.tum", slow);
    std::vector<bool> every(walk.times.size(), true), even(walk.times.size(), false);
    for (std::size_t i = 0; i < even.size(); i += 2) even[i] = true;
    const Paired at_5x = PairAgainst(walk, dir / "fast.tum", every);
    const Paired at_half = PairAgainst(walk, dir / "slow.tum", even);
    std::printf("APE RMSE: per-scan reference %.4f m (%zu scans); 5x %.4f m (%zu paired); 0.5x %.4f m (%zu paired, "
                "the 0.5x reference itself %.4f m RMS off the per-scan one)\n",
                per_scan, walk.times.size(), at_5x.ape, at_5x.scans, at_half.ape, at_half.scans, at_half.interpolation_rms);
    // The pairing: a scan whose stamp is in the file gets that pose, whatever the rate.
    EXPECT_LT(at_5x.max_exact_error, 1e-6);
    EXPECT_LT(at_half.max_exact_error, 1e-6);
    EXPECT_EQ(at_5x.scans, walk.times.size());
    EXPECT_NEAR(at_5x.ape, per_scan, 0.01);
    // 0.5x: scan 1 lies in the walk's 6.4 s pause between two kept poses (longer than the gap limit)
    // and is left out, never given a pose from across the pause; so is the last scan, 0.9 s past the
    // last kept pose. Between kept poses (key frames up to 2.4 s apart) the cubic follows the walk's
    // curve but not its sway: the APE moves by at most that reference error, and by less than 1 cm.
    EXPECT_EQ(at_half.scans, walk.times.size() - 2);
    EXPECT_LE(std::abs(at_half.ape - per_scan), at_half.interpolation_rms + 1e-3);
    EXPECT_NEAR(at_half.ape, per_scan, 0.01);
}

}  // namespace
}  // namespace revisit
