/// Reader throughput on real KITTI scans (issue: a 120k-point scan must read in under 5 ms).
#include "bench_main.hpp"

#include <filesystem>

#include "io/cloud_files.hpp"
#include "io/reader.hpp"

namespace {
std::filesystem::path KittiDir() { return revisit::bench::DataDir() / "kitti00_first16"; }

void BM_LoadKittiBin(benchmark::State& state) {
    const auto file = KittiDir() / "velodyne/000000.bin";
    if (!revisit::bench::NeedData(state, file)) return;
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
    if (!revisit::bench::NeedData(state, KittiDir())) return;
    std::size_t scans = 0;
    for (auto _ : state) {
        auto reader = revisit::OpenDataset(KittiDir());
        while (auto scan = reader->Next()) ++scans;
    }
    state.counters["scans/s"] = benchmark::Counter(static_cast<double>(scans), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_KittiReaderSequence)->Unit(benchmark::kMillisecond);
}  // namespace

REVISIT_BENCHMARK_MAIN()
