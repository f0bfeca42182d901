/// Speed of the optimization module (issue 6): a 1,000-node graph with 200 closures, and the
/// refinement of one closure between ~100 m maps. Fixtures come from tests/optimization.
#include "bench_main.hpp"
#include <tbb/global_control.h>

#include <filesystem>

#include "core/se3.hpp"
#include "../tests/optimization/cloud_fixtures.hpp"  // test fixtures; microbench/ has no tests/ include path
#include "../tests/optimization/drift_simulation.hpp"
#include "optimization/pose_graph.hpp"
#include "optimization/refinement.hpp"

namespace revisit {
namespace {

struct Graph {
    Poses odometry;
    std::vector<PoseGraphEdge> edges;
};

/// 1,000 nodes on the ~4.6 km city route, 200 true closures (+ `wrong` wrong ones).
Graph MakeGraph(int wrong) {
    const auto truth = testing::CityRoute(4.64);
    Graph graph;
    graph.odometry = testing::DriftingOdometry(truth, testing::DriftModel{});
    graph.odometry.resize(std::min<std::size_t>(1000, graph.odometry.size()));
    graph.edges = OdometryEdges(graph.odometry, DiagonalInformation(0.07, 0.002));
    const Poses nodes(truth.begin(), truth.begin() + static_cast<std::ptrdiff_t>(graph.odometry.size()));
    const auto closures = testing::TrueClosures(nodes, 8.0, 200.0, 1, DiagonalInformation(0.1, 0.005), 17);
    const double stride = static_cast<double>(closures.size()) / 200.0;
    for (int k = 0; k < 200 && stride >= 1.0; ++k) graph.edges.push_back(closures[static_cast<std::size_t>(k * stride)]);
    const auto false_closures = testing::FalseClosures(nodes, wrong, 50.0, DiagonalInformation(0.1, 0.005), 23);
    graph.edges.insert(graph.edges.end(), false_closures.begin(), false_closures.end());
    return graph;
}

void BM_OptimizePoseGraph(benchmark::State& state) {
    const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
    const auto graph = MakeGraph(static_cast<int>(state.range(1)));
    PoseGraphConfig config;
    config.loop_loss = state.range(2) != 0 ? RobustLossKind::kDynamicCovarianceScaling : RobustLossKind::kCauchy;
    config.anneal = state.range(2) != 0;
    PoseGraphResult result;
    for (auto _ : state) result = OptimizePoseGraph(graph.odometry, graph.edges, config);
    state.counters["nodes"] = static_cast<double>(graph.odometry.size());
    state.counters["closures"] = static_cast<double>(graph.edges.size() - (graph.odometry.size() - 1));
    state.counters["iterations"] = result.iterations;
}
// Args: threads, wrong closures, DCS with annealing (1) or Cauchy (0).
BENCHMARK(BM_OptimizePoseGraph)->Args({1, 0, 0})->Args({2, 0, 0})->Args({2, 20, 0})->Args({2, 20, 1})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

/// Reference and query: two disjoint halves of a real KITTI scan (~80 m radius), the query
/// moved by a known pose, the guess off by 0.5 m and 2 degrees.
void BM_RefineAlignmentKitti(benchmark::State& state) {
    const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
    const auto file = bench::DataDir() / "kitti00_first16/velodyne/000000.bin";
    if (!bench::NeedData(state, file)) return;
    const auto scan = testing::ReadKittiBin(file);
    const auto ref = testing::Subsample(scan, 2, 0);
    const Eigen::Isometry3d T_true = PoseFromXYZRPY(15.0, -4.0, 0.3, 0.017, -0.009, 0.61);
    const auto query = testing::Transform(T_true, testing::Subsample(scan, 2, 1));
    Eigen::Isometry3d perturbation = Eigen::Isometry3d::Identity();
    perturbation.linear() = ExpSO3(Eigen::Vector3d(0.0, 0.0, 2.0 * M_PI / 180.0));
    perturbation.translation() = Eigen::Vector3d(0.3, 0.4, 0.0);
    RefinementResult result;
    for (auto _ : state) result = RefineAlignment(ref, query, T_true * perturbation, RefinementConfig{});
    state.counters["points"] = static_cast<double>(ref.size() + query.size());
    state.counters["iterations"] = result.iterations;
    state.counters["error_cm"] = 100.0 * (T_true.inverse() * result.T_query_ref).translation().norm();
}
BENCHMARK(BM_RefineAlignmentKitti)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Two 100 m synthetic streets (same street sampled twice).
void BM_RefineAlignmentStreet(benchmark::State& state) {
    const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
    const auto street = testing::SyntheticStreet(100.0, 20.0, 3);
    const auto ref = testing::Subsample(street, 2, 0);
    const Eigen::Isometry3d T_true = PoseFromXYZRPY(-20.0, 3.0, 0.0, 0.0, 0.0, -1.0);
    const auto query = testing::Transform(T_true, testing::Subsample(street, 2, 1));
    const Eigen::Isometry3d guess = T_true * PoseFromXYZRPY(0.4, -0.3, 0.0, 0.0, 0.0, 0.035);
    RefinementResult result;
    for (auto _ : state) result = RefineAlignment(ref, query, guess, RefinementConfig{});
    state.counters["points"] = static_cast<double>(ref.size() + query.size());
    state.counters["iterations"] = result.iterations;
}
BENCHMARK(BM_RefineAlignmentStreet)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace revisit

REVISIT_BENCHMARK_MAIN()
