/// Closure-detection cases (METHOD.md sections 3-5): density image, ORB, RANSAC per candidate, and the
/// Hamming tree's query+insert as the database grows (the scaling curve).
#include <chrono>
#include <memory>
#include <random>

#include "bench_suite/cases.hpp"
#include "bench_suite/machine.hpp"
#include "closures/descriptor_matching.hpp"
#include "closures/detector.hpp"
#include "core/se3.hpp"

namespace revisit {

namespace {
struct MapSource {
    std::string label;
    LocalMap map;
};

/// A ~100 m simulated city map, plus the first 16 real KITTI scans when present.
std::vector<MapSource> Maps(const CaseContext& c) {
    std::vector<MapSource> maps;
    const auto& sim = c.fixtures->Simulated("city-64", c.scale.map_scans);
    maps.push_back({"sim city-64", AccumulateMap(sim, 0, sim.size() - 1, 0)});
    if (c.Need("kitti00_first16", "closures on kitti00 0-15")) {
        const auto& kitti = c.fixtures->Dataset(c.data_dir / "kitti00_first16", 16);
        if (kitti.size() == 16 && kitti[0].T_world_sensor)
            maps.push_back({"kitti00 0-15", AccumulateMap(kitti, 0, 15, 0)});
    }
    return maps;
}

LocalMap Moved(LocalMap map, const Eigen::Isometry3d& T) {
    const Eigen::Isometry3f Tf = T.cast<float>();
    for (auto& p : map.points) p = Tf * p;
    return map;
}

/// Descriptor sets of the same place seen from other poses (random yaw and shift).
std::vector<Features> Variants(const LocalMap& map, int count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> yaw(-M_PI, M_PI), shift(-20.0, 20.0);
    std::vector<Features> variants;
    const auto config = ClosureDetectorConfig::Paper();
    for (int v = 0; v < count; ++v) {
        const auto moved = Moved(map, PoseFromXYZRPY(shift(rng), shift(rng), 0, 0, 0, yaw(rng)));
        variants.push_back(ComputeMapFeatures(moved, config).features);
    }
    return variants;
}
}  // namespace

void ClosureStageCases(const CaseContext& c) {
    const auto config = ClosureDetectorConfig::Paper();
    for (const auto& [label, map] : Maps(c)) {
        const std::string points = std::to_string(map.points.size()) + " map points";
        {
            Measurement measured =
                Measure("closures/density image " + label, "ms/map", FigureKind::kMsPerItem, c.scale.repeat,
                        [&] { return ComputeDensityImage(map.points, config.density).image.empty() ? 0.0 : 1.0; });
            c.Add(std::move(measured), "ComputeDensityImage, 0.5 m pixels, " + points);
        }
        const auto density = ComputeDensityImage(map.points, config.density);
        std::size_t keypoints = 0;
        {
            Measurement measured =
                Measure("closures/ORB " + label, "ms/map", FigureKind::kMsPerItem, c.scale.repeat, [&] {
                    keypoints = ComputeFeatures(density.image, config.features).keypoints.size();
                    return 1.0;
                });
            c.Add(std::move(measured), "ComputeFeatures, " + std::to_string(density.image.cols) + "x" +
                                           std::to_string(density.image.rows) + " pixels, " +
                                           std::to_string(keypoints) + " keypoints");
        }

        // RANSAC of one candidate: the map against itself moved by a known yaw and shift, matched
        // through the tree as the detector does (METHOD.md section 5).
        const auto ref = ComputeMapFeatures(map, config);
        const auto query = ComputeMapFeatures(Moved(map, PoseFromXYZRPY(6.0, -4.0, 0, 0, 0, 0.7)), config);
        HammingTree tree(config.tree);
        tree.Add(ref.features.descriptors, 0);
        // A match as RANSAC sees it: both keypoints in metres, weighted by the descriptor distance.
        const auto point_pair = [&](std::int32_t query_keypoint, std::int32_t ref_keypoint, std::int32_t distance) {
            const auto& kr = ref.features.keypoints[std::size_t(ref_keypoint)];
            const auto& kq = query.features.keypoints[std::size_t(query_keypoint)];
            return PointPair{ref.density.ToMetric(kr.x(), kr.y()), query.density.ToMetric(kq.x(), kq.y()),
                             double(config.tree.max_distance - distance)};
        };
        std::vector<PointPair> pairs;
        for (const auto& m : tree.Match(query.features.descriptors)) pairs.push_back(point_pair(m.query, m.keypoint, m.distance));
        if (pairs.size() < 2) {
            c.Skip("closures/RANSAC " + label + ": fewer than 2 matches");
            continue;
        }
        int inliers = 0;
        {
            Measurement measured =
                Measure("closures/RANSAC " + label, "ms/candidate", FigureKind::kMsPerItem, c.scale.repeat, [&] {
                    std::mt19937 rng(config.ransac.seed);
                    inliers = AlignRansac2D(pairs, config.ransac, rng).num_inliers;
                    return 1.0;
                });
            c.Add(std::move(measured), "AlignRansac2D, default sampling (every pair, best first), " + std::to_string(pairs.size()) +
                                           " matches, " + std::to_string(inliers) + " inliers");
        }
        // The default detector's verification (detector.rematch): every mutual best match between the
        // two maps' descriptors, then RANSAC on those; this is its cost per candidate on top of the tree's.
        {
            int rematched = 0;
            std::size_t matched = 0;
            Measurement measured =
                Measure("closures/rematch candidate " + label, "ms/candidate", FigureKind::kMsPerItem, c.scale.repeat, [&] {
                    const auto matches = MatchMutualBest(query.features.descriptors, ref.features.descriptors,
                                                         config.tree.max_distance);
                    std::vector<PointPair> mutual;
                    for (const auto& m : matches) mutual.push_back(point_pair(m.query_keypoint, m.ref_keypoint, m.distance));
                    matched = mutual.size();
                    std::mt19937 rng(config.ransac.seed);
                    rematched = mutual.size() < 2 ? 0 : AlignRansac2D(mutual, config.ransac, rng).num_inliers;
                    return 1.0;
                });
            c.Add(std::move(measured), "MatchMutualBest (" + std::to_string(query.features.descriptors.size()) + " x " +
                                           std::to_string(ref.features.descriptors.size()) + " descriptors) + AlignRansac2D, " +
                                           std::to_string(matched) + " mutual matches, " + std::to_string(rematched) +
                                           " inliers");
        }
        // A wrong candidate (same matches, query points shuffled): no early stop, every pair is tried.
        // This is the expensive case: most candidates of the paper's top-half selection are wrong.
        std::mt19937 shuffle_rng(11);
        for (std::size_t i = pairs.size() - 1; i > 0; --i)
            std::swap(pairs[i].query, pairs[std::uniform_int_distribution<std::size_t>(0, i)(shuffle_rng)].query);
        RansacResult wrong;
        {
            Measurement measured = Measure("closures/RANSAC wrong candidate " + label, "ms/candidate",
                                           FigureKind::kMsPerItem, c.scale.repeat, [&] {
                                               std::mt19937 rng(config.ransac.seed);
                                               wrong = AlignRansac2D(pairs, config.ransac, rng);
                                               return 1.0;
                                           });
            c.Add(std::move(measured), "AlignRansac2D on shuffled matches, " + std::to_string(pairs.size()) +
                                           " matches, " + std::to_string(wrong.trials) + " pairs, " +
                                           std::to_string(wrong.hypotheses) + " scored, " +
                                           std::to_string(wrong.num_inliers) + " inliers");
        }
    }
}

/// Leaf entries a query compares against: with many near-identical maps the scan is memory-bound.
std::size_t ScannedEntries(const HammingTree& tree, const std::vector<Descriptor>& query) {
    std::size_t scanned = 0;
    for (const auto& d : query) scanned += tree.LeafOf(d).size();
    return scanned;
}

void TreeCases(const CaseContext& c) {
    const auto maps = Maps(c);
    const auto& source = maps.back();  // real data when present
    const auto variants = Variants(source.map, 16, 3);
    const auto config = ClosureDetectorConfig::Paper();
    HammingTree tree(config.tree);
    std::mt19937_64 rng(7);
    std::int32_t next_id = 0;
    // Stored maps are re-observations of the place: a variant with a few bits flipped per descriptor,
    // so the leaves fill with near duplicates as in a long drive through one city.
    const auto add_map = [&] {
        auto descriptors = variants[std::size_t(next_id) % variants.size()].descriptors;
        for (auto& d : descriptors) {
            for (int k = 0; k < 4; ++k) {
                const int bit = int(rng() % 256);
                d[std::size_t(bit >> 6)] ^= std::uint64_t(1) << (bit & 63);
            }
        }
        tree.Add(descriptors, next_id++);
    };
    const auto& query = variants[5].descriptors;
    for (const int size : c.scale.database_sizes) {
        while (next_id < size) add_map();
        std::size_t matches = 0;
        MeasureConfig repeat{1, c.scale.tree_queries};
        {
            // Every repetition queries and inserts at exactly `size` maps: it works on a copy of the tree,
            // made and freed outside the timed region (issue 19: the figure is the size it names).
            Measurement measured = MeasureValue(
                "tree/query+insert " + std::to_string(size) + " maps", "ms/map", FigureKind::kMsPerItem, repeat, [&] {
                    auto copy = std::make_unique<HammingTree>(tree);
                    const auto start = std::chrono::steady_clock::now();
                    matches = copy->MatchAndAdd(query, next_id).size();
                    const auto stop = std::chrono::steady_clock::now();
                    copy.reset();
                    return std::chrono::duration<double, std::milli>(stop - start).count();
                });
            c.Add(std::move(measured),
                  "HammingTree::MatchAndAdd, " + std::to_string(query.size()) + " descriptors of " + source.label +
                      " against " + std::to_string(tree.size()) + " stored, depth " + std::to_string(tree.depth()) +
                      ", " + std::to_string(matches) + " matches, " +
                      std::to_string(tree.MemoryBytes() / std::size_t(next_id)) + " B/map, " +
                      std::to_string(ScannedEntries(tree, query)) + " entries scanned");
        }
    }
}

/// Issue 20's scale question: one database holding many sessions of a city. Every place is seen by 8
/// sessions; a place's descriptors are a real map's with 24 random bits flipped each (distinct places,
/// ORB-like bit statistics), an observation flips 4 more. Maps are inserted session by session, as
/// `revisit merge` does; each timed query is a new observation of a stored place.
void FleetTreeCases(const CaseContext& c) {
    constexpr int kSessions = 8;
    const auto maps = Maps(c);
    const auto& source = maps.back();
    const auto variants = Variants(source.map, 16, 3);
    const auto config = ClosureDetectorConfig::Paper();
    std::mt19937_64 rng(11);
    const auto flip = [&rng](std::vector<Descriptor> descriptors, int bits) {
        for (auto& d : descriptors) {
            for (int k = 0; k < bits; ++k) {
                const int bit = int(rng() % 256);
                d[std::size_t(bit >> 6)] ^= std::uint64_t(1) << (bit & 63);
            }
        }
        return descriptors;
    };
    for (const int size : c.scale.fleet_database_sizes) {
        const int places = std::max(1, size / kSessions);
        std::vector<std::vector<Descriptor>> place(static_cast<std::size_t>(places));
        for (int p = 0; p < places; ++p) place[std::size_t(p)] = flip(variants[std::size_t(p) % variants.size()].descriptors, 24);
        HammingTree tree(config.tree);
        std::int32_t next_id = 0;
        const auto insert_start = std::chrono::steady_clock::now();
        for (int session = 0; session < kSessions; ++session)
            for (int p = 0; p < places && next_id < size; ++p) tree.Add(flip(place[std::size_t(p)], 4), next_id++);
        const double insert_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - insert_start).count();
        std::size_t matches = 0;
        int query_place = 0;
        Measurement measured = Measure("fleet_tree/query+insert " + std::to_string(size) + " maps", "ms/map", FigureKind::kMsPerItem,
                                       MeasureConfig{1, c.scale.tree_queries}, [&] {
                                           const auto query = flip(place[std::size_t(query_place++ * 7919 % places)], 4);
                                           matches = tree.MatchAndAdd(query, next_id++).size();
                                           return 1.0;
                                       });
        c.Add(std::move(measured), std::to_string(kSessions) + " sessions x " + std::to_string(places) + " places of " +
                                       source.label + "; building by insertion " +
                                       std::to_string(insert_ms / std::max(1, size)) + " ms/map; " +
                                       std::to_string(tree.MemoryBytes() / std::size_t(next_id)) + " B/map in the tree, depth " +
                                       std::to_string(tree.depth()) + ", " + std::to_string(matches) + " matches; peak RSS " +
                                       std::to_string(PeakMemoryKb() / 1024) + " MiB");
    }
}

}  // namespace revisit
