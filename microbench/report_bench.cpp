// Rendering and report benchmarks (issue 8 quality bar: a report with 100 closures in under 60 s on 2 cores).
// Synthetic run: loop through a box world, local maps of ~20-40k points, 80 matches per closure.
#include "bench_main.hpp"

#include "render/overview.hpp"
#include "report/report_writer.hpp"
#include "report/synthetic_report.hpp"

#include <filesystem>
#include <random>

namespace {

std::filesystem::path ScratchDir(const std::string& name) {
    std::random_device device;
    const auto dir = std::filesystem::temp_directory_path() / ("revisit-bench-" + name + std::to_string(device()));
    std::filesystem::create_directories(dir);
    return dir;
}

void BM_ClosurePage(benchmark::State& state) {
    revisit::SyntheticRunConfig config;
    config.num_closures = 10;
    const auto input = revisit::MakeSyntheticRun(config);
    const auto dir = ScratchDir("page");
    std::size_t i = 0;
    for (auto _ : state) revisit::WriteClosurePage(input, i++ % input.closures.size(), dir);
    std::filesystem::remove_all(dir);
}
BENCHMARK(BM_ClosurePage)->Unit(benchmark::kMillisecond);

void BM_OverviewTopDown(benchmark::State& state) {
    revisit::SyntheticRunConfig config;
    config.num_closures = 100;
    const auto input = revisit::MakeSyntheticRun(config);
    revisit::OverviewData data;
    data.map_points = input.load_global_map();
    for (const auto& T : input.odometry.T_world_sensor) data.odometry.push_back(T.translation());
    for (const auto& T : input.corrected.T_world_sensor) data.corrected.push_back(T.translation());
    for (auto _ : state) benchmark::DoNotOptimize(revisit::RenderOverview(data, revisit::OverviewView::kTopDown));
    state.counters["points"] = double(data.map_points.size());
}
BENCHMARK(BM_OverviewTopDown)->Unit(benchmark::kMillisecond);

void BM_Report(benchmark::State& state) {
    revisit::SyntheticRunConfig config;
    config.num_closures = int(state.range(0));
    const auto input = revisit::MakeSyntheticRun(config);
    for (auto _ : state) {
        const auto dir = ScratchDir("report");
        const auto stats = revisit::WriteReport(input, dir);
        state.counters["pages"] = stats.pages;
        state.counters["files"] = stats.images;
        std::filesystem::remove_all(dir);
    }
}
BENCHMARK(BM_Report)->Arg(100)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

REVISIT_BENCHMARK_MAIN()
