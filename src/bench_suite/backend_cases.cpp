/// Back-end cases: refinement per closure, the pose graph over a (nodes x closures) grid, the online
/// closure-consistency check per map, ground-truth closure generation and the ScanContext baseline's
/// search per scan, and report rendering per closure.
#include <algorithm>
#include <cmath>
#include <random>

#include "bench_suite/cases.hpp"
#include "core/se3.hpp"
#include "evaluation/ground_truth_closures.hpp"
#include "evaluation/scan_context.hpp"
#include "optimization/closure_consistency.hpp"
#include "optimization/map_overlap.hpp"
#include "optimization/pose_graph.hpp"
#include "optimization/refinement.hpp"
#include "report/report_writer.hpp"
#include "report/synthetic_report.hpp"

namespace revisit {

namespace {
/// Expensive cases get fewer repetitions than the stage micro-figures.
MeasureConfig Heavy(const SuiteScale& scale) { return {0, std::max(2, scale.repeat.repetitions / 2)}; }

/// Every other point of `map`, as doubles, transformed by T.
std::vector<Eigen::Vector3d> Half(const LocalMap& map, int parity, const Eigen::Isometry3d& T) {
    std::vector<Eigen::Vector3d> out;
    for (std::size_t i = std::size_t(parity); i < map.points.size(); i += 2)
        out.push_back(T * map.points[i].cast<double>());
    return out;
}

/// A drive of `laps` laps around a 400 m loop, one pose per `step` m (a route with revisits).
Poses LoopRoute(std::size_t n, double step) {
    Poses poses;
    const double radius = 400.0 / (2.0 * M_PI);
    for (std::size_t i = 0; i < n; ++i) {
        const double angle = step * double(i) / radius;
        poses.push_back(PoseFromXYZRPY(radius * std::cos(angle), radius * std::sin(angle), 0, 0, 0, angle + M_PI / 2));
    }
    return poses;
}
}  // namespace

void RefinementCases(const CaseContext& c) {
    const auto& sim = c.fixtures->Simulated("city-64", c.scale.map_scans);
    const LocalMap map = AccumulateMap(sim, 0, sim.size() - 1, 0);
    // Reference and query: disjoint halves of one ~100 m map, the query moved by a known pose and the
    // RANSAC-like guess off by 0.4 m and 2 degrees (METHOD.md section 6).
    const Eigen::Isometry3d T_true = PoseFromXYZRPY(15.0, -4.0, 0.3, 0.017, -0.009, 0.61);
    const auto ref = Half(map, 0, Eigen::Isometry3d::Identity());
    const auto query = Half(map, 1, T_true);
    const Eigen::Isometry3d guess = T_true.inverse() * PoseFromXYZRPY(0.3, 0.25, 0, 0, 0, 0.035);
    int iterations = 0;
    {
        Measurement measured =
            Measure("refinement/closure sim city-64", "ms/closure", FigureKind::kMsPerItem, c.scale.repeat, [&] {
                iterations = RefineAlignment(ref, query, guess, RefinementConfig{}).iterations;
                return 1.0;
            });
        c.Add(std::move(measured), "RefineAlignment, " + std::to_string(ref.size() + query.size()) + " points, " +
                                       std::to_string(iterations) + " iterations");
    }
    {
        // The proximity pass: one query map prepared once, registered with several references from
        // guesses within a closure's error and no vertical search.
        RefinementConfig confirm;
        confirm.vertical_search = 0.0;
        std::vector<Eigen::Isometry3d> guesses;
        for (int k = 0; k < 3; ++k) guesses.push_back(T_true.inverse() * PoseFromXYZRPY(0.1 * k, -0.05 * k, 0, 0, 0, 0.005 * k));
        Measurement measured = Measure("refinement/prepared query, 3 references", "ms/closure", FigureKind::kMsPerItem,
                                       c.scale.repeat, [&] {
                                           const RefinementQuery prepared(query, confirm);
                                           for (const auto& g : guesses) iterations = RefineAlignment(ref, prepared, g, confirm).iterations;
                                           return double(guesses.size());
                                       });
        c.Add(std::move(measured), "RefinementQuery once, then RefineAlignment x3 (proximity pass)");
    }
}

void PoseGraphCases(const CaseContext& c) {
    for (const auto& [nodes, closures] : c.scale.graph_grid) {
        // Nodes every 2 m around a 400 m loop; odometry with a yaw drift; closures tie a node to the
        // same place one lap earlier (exact relative poses).
        const Poses truth = LoopRoute(std::size_t(nodes), 2.0);
        Poses odometry{truth[0]};
        for (std::size_t i = 1; i < truth.size(); ++i)
            odometry.push_back(odometry.back() * PoseFromXYZRPY(0, 0, 0, 0, 0, 0.002) * truth[i - 1].inverse() *
                               truth[i]);
        auto edges = OdometryEdges(odometry, DiagonalInformation(0.07, 0.002));
        const int per_lap = 200;
        const int available = std::max(0, nodes - per_lap);
        for (int k = 0; k < closures && available > 0; ++k) {
            const int to = per_lap + int(std::int64_t(k) * available / closures);
            PoseGraphEdge e;
            e.from = to - per_lap;
            e.to = to;
            e.T_from_to = truth[std::size_t(e.from)].inverse() * truth[std::size_t(e.to)];
            e.information = DiagonalInformation(0.1, 0.005);
            e.is_loop = true;
            edges.push_back(e);
        }
        int iterations = 0;
        {
            Measurement measured =
                Measure("pose_graph/" + std::to_string(nodes) + " nodes x " + std::to_string(closures) + " closures",
                        "ms/solve", FigureKind::kMsPerItem, Heavy(c.scale), [&] {
                            iterations = OptimizePoseGraph(odometry, edges, PoseGraphConfig{}).iterations;
                            return 1.0;
                        });
            c.Add(std::move(measured),
                  "OptimizePoseGraph, Cauchy, drifted start, " + std::to_string(iterations) + " iterations");
        }
    }
}

void ConsistencyCases(const CaseContext& c) {
    // Worst case for the pairwise check: maps every 10 m around a 400 m loop, each map after the first
    // lap closing with the map one lap earlier, one closure in ten wrong by 5 m and 0.1 rad; the
    // whole online sequence (one row of the table and one maximum-consistent-set search per closure).
    const std::size_t maps = std::size_t(c.scale.consistency_maps);
    const Poses truth = LoopRoute(maps, 10.0);
    Poses odometry{truth[0]};
    std::vector<double> travel{0.0};
    for (std::size_t i = 1; i < maps; ++i) {
        odometry.push_back(odometry.back() * PoseFromXYZRPY(0, 0, 0, 0, 0, 5e-4) * truth[i - 1].inverse() * truth[i]);
        travel.push_back(10.0 * double(i));
    }
    const std::size_t per_lap = 40;
    std::size_t kept = 0, closures = 0;
    Measurement measured = Measure("consistency/" + std::to_string(maps) + " maps", "ms/map", FigureKind::kMsPerItem,
                                   Heavy(c.scale), [&] {
                                       ClosureConsistency consistency(ClosureConsistencyConfig{}, OdometryNoise{});
                                       std::vector<char> keep;
                                       for (std::size_t q = per_lap; q < maps; ++q) {
                                           const std::size_t r = q - per_lap;
                                           Eigen::Isometry3d T = truth[q].inverse() * truth[r];
                                           if (q % 10 == 0) T = T * PoseFromXYZRPY(5.0, 0, 0, 0, 0, 0.1);
                                           consistency.Add({int(q), int(r), T, 20.0}, {&odometry, &travel});
                                           keep = consistency.ConsistentSet();
                                       }
                                       closures = keep.size();
                                       kept = std::size_t(std::count(keep.begin(), keep.end(), 1));
                                       return double(maps);
                                   });
    c.Add(std::move(measured), "ClosureConsistency::Add + ConsistentSet after every closure, " + std::to_string(closures) +
                                   " closures (1 in 10 wrong), " + std::to_string(kept) + " kept at the end");
}

void ProximityCases(const CaseContext& c) {
    // The proximity pass's prediction (registrations are the refinement's figure): the same loop's maps,
    // each with a footprint of 1,000 cells (a 40 x 25 cell block, 1 m cells), paired by PredictOverlaps
    // from the true poses; every map overlaps its neighbours and the maps one lap away.
    const std::size_t maps = std::size_t(c.scale.consistency_maps);
    const Poses poses = LoopRoute(maps, 10.0);
    std::vector<Eigen::Vector2d> block;
    for (int x = -20; x < 20; ++x)
        for (int y = -12; y <= 12; ++y) block.emplace_back(x + 0.5, y + 0.5);
    const std::vector<std::vector<Eigen::Vector2d>> footprints(maps, block);
    std::size_t pairs = 0;
    Measurement measured = Measure("proximity/" + std::to_string(maps) + " maps", "ms/map", FigureKind::kMsPerItem,
                                   Heavy(c.scale), [&] {
                                       pairs = PredictOverlaps(footprints, poses, 1.0, 0.3, 3, [](int q, int r) { return q == r + 1; }).size();
                                       return double(maps);
                                   });
    c.Add(std::move(measured), "PredictOverlaps over " + std::to_string(maps) + " footprints of " + std::to_string(block.size()) +
                                   " cells, " + std::to_string(pairs) + " pairs to register");
}

void GroundTruthCases(const CaseContext& c) {
    // Cost per scan: the simulated (or real) scans cycled over a multi-lap loop, so the segments
    // revisit each other as in a real sequence; the overlaps themselves are not meaningful.
    std::vector<const Scan*> source;
    std::string label = "sim city-64 scans";
    if (c.Need("kitti00_first16", "ground_truth on KITTI scans (ran on simulated scans instead)")) {
        for (const auto& s : c.fixtures->Dataset(c.data_dir / "kitti00_first16", 16)) source.push_back(&s);
        label = "KITTI 00 scans 0-15";
    }
    if (source.empty()) {
        for (const auto& s : c.fixtures->Simulated("city-64", c.scale.map_scans)) source.push_back(&s);
        label = "sim city-64 scans";
    }
    const Poses route = LoopRoute(c.scale.gt_scans, 0.8);
    const ScanPointsFn points = [&](std::size_t i) { return source[i % source.size()]->points; };
    std::size_t closures = 0;
    {
        Measurement measured = Measure("ground_truth/closures", "ms/scan", FigureKind::kMsPerItem, Heavy(c.scale), [&] {
            closures = ComputeGroundTruthClosures(route, points, GtClosureConfig{}).segment_pairs.size();
            return double(route.size());
        });
        c.Add(std::move(measured), "ComputeGroundTruthClosures, " + std::to_string(route.size()) +
                                       " scans over a 400 m loop (" + label + " cycled), " + std::to_string(closures) +
                                       " closing segment pairs");
    }
}

void ScanContextCases(const CaseContext& c) {
    // Synthetic descriptors of a drive: each scan's bins a small step from the one before, so the ring
    // keys spread as a sequence's do. The figure per scan must not grow with the sequence.
    const ScanContextConfig config;
    for (const std::size_t n : c.scale.scan_context_scans) {
        std::mt19937 rng(7);
        std::normal_distribution<float> step(0.0f, 0.1f);
        std::vector<ScanContextDescriptor> descriptors(n);
        Eigen::MatrixXf bins = Eigen::MatrixXf::Constant(config.num_rings, config.num_sectors, 1.0f);
        for (auto& d : descriptors) {
            for (Eigen::Index k = 0; k < bins.size(); ++k) bins(k) = std::max(0.0f, bins(k) + step(rng));
            d = DescriptorOfBins(bins);
        }
        std::size_t candidates = 0;
        Measurement measured = Measure("scan_context/search", "ms/scan", FigureKind::kMsPerItem, Heavy(c.scale), [&] {
            candidates = SearchScanContext(descriptors, config).size();
            return double(n);
        });
        c.Add(std::move(measured), "SearchScanContext over " + std::to_string(n) + " synthetic descriptors, " +
                                       std::to_string(candidates) + " candidates verified");
    }
}

void ReportCases(const CaseContext& c) {
    SyntheticRunConfig config;
    config.num_closures = c.scale.report_closures;
    const ReportInput input = MakeSyntheticRun(config);
    const auto dir = c.scratch_dir / "report";
    std::filesystem::create_directories(dir);
    {
        Measurement measured =
            Measure("report/closure page", "ms/closure", FigureKind::kMsPerItem, Heavy(c.scale), [&] {
                for (std::size_t i = 0; i < input.closures.size(); ++i) WriteClosurePage(input, i, dir);
                return double(input.closures.size());
            });
        c.Add(std::move(measured), "WriteClosurePage (offscreen renders, density pictures, HTML), synthetic run, " +
                                       std::to_string(input.closures.size()) + " closures");
    }
}

}  // namespace revisit
