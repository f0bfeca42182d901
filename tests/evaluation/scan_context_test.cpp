#include "evaluation/scan_context.hpp"
#include "evaluation/scan_context_file.hpp"
#include "test_data.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <random>

namespace revisit {
namespace {
namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

TEST(MakeScanContext, BinValuesOfAConstructedCloud) {
    const std::vector<Eigen::Vector3f> points = {
        {10.0f, 0.0f, 1.0f},     // r 10 -> ring ceil(2.5) = 3 -> row 2; azimuth 0 -> sector 1 -> col 0; 1 + 2 = 3
        {10.0f, 0.0f, -0.5f},    // same bin, lower: the maximum stays 3
        {0.0f, 30.0f, 0.5f},     // r 30 -> row 7; 90 deg -> ceil(15) -> col 14; 2.5
        {-50.0f, -50.0f, 1.0f},  // r 70.7 -> ceil(17.7) = 18 -> row 17; 225 deg -> ceil(37.5) -> col 37; 3
        {5.0f, 5.0f, -3.0f},     // r 7.07 -> row 1; 45 deg -> ceil(7.5) -> col 7; -1 (below the ground)
        {90.0f, 0.0f, 5.0f},     // beyond 80 m: ignored
    };
    const ScanContextConfig config;
    const auto descriptor = MakeScanContext(points, config);
    ASSERT_EQ(descriptor.bins.rows(), 20);
    ASSERT_EQ(descriptor.bins.cols(), 60);
    EXPECT_FLOAT_EQ(descriptor.bins(2, 0), 3.0f);
    EXPECT_FLOAT_EQ(descriptor.bins(7, 14), 2.5f);
    EXPECT_FLOAT_EQ(descriptor.bins(17, 37), 3.0f);
    EXPECT_FLOAT_EQ(descriptor.bins(1, 7), -1.0f);
    EXPECT_FLOAT_EQ(descriptor.bins.cwiseAbs().sum(), 9.5f);  // every other bin is empty = 0
    EXPECT_FLOAT_EQ(descriptor.ring_key(2), 3.0f / 60.0f);
    EXPECT_FLOAT_EQ(descriptor.ring_key(0), 0.0f);
    EXPECT_FLOAT_EQ(descriptor.sector_key(37), 3.0f / 20.0f);
}

std::vector<Eigen::Vector3f> RandomCloud(std::mt19937& rng, std::size_t count = 3000) {
    std::uniform_real_distribution<float> xy(-70.0f, 70.0f), z(-1.5f, 6.0f);
    std::vector<Eigen::Vector3f> points;
    for (std::size_t k = 0; k < count; ++k) points.emplace_back(xy(rng), xy(rng), z(rng));
    return points;
}

std::vector<Eigen::Vector3f> RotateAboutZ(const std::vector<Eigen::Vector3f>& points, double angle) {
    const Eigen::Matrix3f R = Eigen::AngleAxisf(static_cast<float>(angle), Eigen::Vector3f::UnitZ()).toRotationMatrix();
    std::vector<Eigen::Vector3f> rotated;
    for (const auto& p : points) rotated.push_back(R * p);
    return rotated;
}

TEST(ScanContextDistance, RotationBySectorsIsAColumnShift) {
    std::mt19937 rng(11);
    const auto cloud = RandomCloud(rng);
    const ScanContextConfig config;
    const auto candidate = MakeScanContext(cloud, config);
    const auto query = MakeScanContext(RotateAboutZ(cloud, 7 * 6.0 * kPi / 180.0 + 1e-4), config);  // 7 sectors
    EXPECT_LT((query.ring_key - candidate.ring_key).norm(), 1e-3);
    const auto match = ScanContextDistance(query, candidate, config);
    EXPECT_EQ(match.shift, 7);
    EXPECT_LT(match.distance, 0.02);
    // An unrelated cloud is far.
    const auto other = MakeScanContext(RandomCloud(rng), config);
    EXPECT_GT(ScanContextDistance(query, other, config).distance, 0.1);
    // Distance to itself is 0.
    EXPECT_NEAR(ScanContextDistance(candidate, candidate, config).distance, 0.0, 1e-6);
}

TEST(SearchScanContext, FollowsTheRebuildScheduleAndFindsTheRevisit) {
    std::mt19937 rng(12);
    const ScanContextConfig config;
    std::vector<std::vector<Eigen::Vector3f>> clouds;
    for (int k = 0; k < 120; ++k) clouds.push_back(RandomCloud(rng, 800));
    clouds[110] = RotateAboutZ(clouds[10], 0.5);  // scan 110 revisits scan 10, turned by 0.5 rad
    std::vector<ScanContextDescriptor> descriptors;
    for (const auto& cloud : clouds) descriptors.push_back(MakeScanContext(cloud, config));

    const auto candidates = SearchScanContext(descriptors, config);
    // Queries 50-99 search scan 0 only (tree built at query 50 from scans [0, 1)); queries 100-119 search
    // scans [0, 51) and verify 10 candidates each.
    ASSERT_EQ(candidates.size(), 50u + 20u * 10u);
    bool found_revisit = false;
    double best_other_of_110 = 2.0, revisit_distance = 2.0;
    for (const auto& c : candidates) {
        if (c.query == 110 && c.candidate != 10) best_other_of_110 = std::min(best_other_of_110, c.distance);
        ASSERT_GE(c.query, 50u);
        EXPECT_LE(c.candidate + 50, c.query);
        if (c.query < 100) {
            EXPECT_EQ(c.candidate, 0u);
        }
        if (c.query == 110 && c.candidate == 10) {
            found_revisit = true;
            revisit_distance = c.distance;
        }
    }
    ASSERT_TRUE(found_revisit);
    EXPECT_LT(revisit_distance, best_other_of_110 - 0.2);  // the revisit is by far the best candidate
    // Held in a scratch file instead of memory: the same candidates, distances bit for bit; the scratch
    // file is an exclusive temporary, gone afterwards, and a file a user has under the name is untouched.
    test::TempDir dir;
    std::ofstream(dir / "sc.scratch") << "a user's file";
    {
        ScanContextFile stored(dir / "sc.scratch", config.num_rings, config.num_sectors);
        for (const auto& descriptor : descriptors) stored.Add(descriptor);
        EXPECT_EQ(stored.Get(37).bins, descriptors[37].bins);
        const auto from_file = SearchScanContext(stored, config);
        ASSERT_EQ(from_file.size(), candidates.size());
        for (std::size_t k = 0; k < candidates.size(); ++k) {
            EXPECT_EQ(from_file[k].query, candidates[k].query);
            EXPECT_EQ(from_file[k].candidate, candidates[k].candidate);
            EXPECT_EQ(from_file[k].distance, candidates[k].distance);
            EXPECT_EQ(from_file[k].shift, candidates[k].shift);
        }
    }
    EXPECT_EQ(test::ReadFile(dir / "sc.scratch"), "a user's file");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
    const auto pairs = ScanContextPairs(candidates);
    ASSERT_EQ(pairs.size(), candidates.size());
    EXPECT_LT(pairs.back().pair.first, pairs.back().pair.second);
}

TEST(SearchScanContext, FromAFileAsFromMemoryOverALongSequence) {
    // Long enough that the search's per-thread descriptor cache reuses its slots, with revisits whose
    // query and candidate share a slot (256 scans apart), and that it runs in more than one run of
    // queries (4096), between which it reports progress.
    std::mt19937 rng(21);
    const ScanContextConfig config;
    std::vector<ScanContextDescriptor> descriptors;
    std::vector<std::vector<Eigen::Vector3f>> clouds;
    for (int k = 0; k < 4400; ++k) clouds.push_back(k >= 256 && k % 3 == 0 ? RotateAboutZ(clouds[std::size_t(k - 256)], 0.1 * k) : RandomCloud(rng, 300));
    for (const auto& cloud : clouds) descriptors.push_back(MakeScanContext(cloud, config));
    const auto candidates = SearchScanContext(descriptors, config);
    test::TempDir dir;
    ScanContextFile stored(dir / "sc.scratch", config.num_rings, config.num_sectors);
    for (const auto& descriptor : descriptors) stored.Add(descriptor);
    std::vector<std::pair<std::size_t, std::size_t>> reported;
    const auto from_file = SearchScanContext(stored, config, [&](std::size_t done, std::size_t total) { reported.emplace_back(done, total); });
    ASSERT_EQ(reported.size(), 2u);
    EXPECT_EQ(reported[0], std::make_pair(std::size_t{config.exclude_recent + 4096}, std::size_t{4400}));
    EXPECT_EQ(reported[1], std::make_pair(std::size_t{4400}, std::size_t{4400}));
    ASSERT_EQ(from_file.size(), candidates.size());
    std::size_t revisits_found = 0;
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        EXPECT_EQ(from_file[k].query, candidates[k].query);
        EXPECT_EQ(from_file[k].candidate, candidates[k].candidate);
        EXPECT_EQ(from_file[k].distance, candidates[k].distance);
        EXPECT_EQ(from_file[k].shift, candidates[k].shift);
        revisits_found += candidates[k].candidate + 256 == candidates[k].query;
    }
    EXPECT_GT(revisits_found, 100u);
}

}  // namespace
}  // namespace revisit
