/// Reader throughput on real KITTI scans (issue: a 120k-point scan must read in under 5 ms).
#include <benchmark/benchmark.h>

#include <filesystem>

#include "io/cloud_files.hpp"
#include "io/reader.hpp"

namespace {
const std::filesystem::path kKitti = std::filesystem::path(REVISIT_SHARED_DIR) / "data/kitti00_first16";

void BM_LoadKittiBin(benchmark::State& state) {
    const auto file = kKitti / "velodyne/000000.bin";
    if (!std::filesystem::exists(file)) {
        state.SkipWithError("../shared/data/kitti00_first16 not available");
        return;
    }
    std::size_t points = 0;
    for (auto _ : state) {
        const auto cloud = revisit::LoadKittiBin(file);
        points = cloud.points.size();
        benchmark::DoNotOptimize(cloud.points.data());
    }
    state.counters["points"] = static_cast<double>(points);
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * points * 16));
}
BENCHMARK(BM_LoadKittiBin)->Unit(benchmark::kMillisecond);

void BM_KittiReaderSequence(benchmark::State& state) {
    if (!std::filesystem::exists(kKitti)) {
        state.SkipWithError("../shared/data/kitti00_first16 not available");
        return;
    }
    std::size_t scans = 0;
    for (auto _ : state) {
        auto reader = revisit::OpenDataset(kKitti);
        while (auto scan = reader->Next()) ++scans;
    }
    state.counters["scans/s"] = benchmark::Counter(static_cast<double>(scans), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_KittiReaderSequence)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
