/// Odometry speed: milliseconds per 64-beam scan, real KITTI scans and simulated ones, with 1 and
/// 2 TBB threads: each scan's own time in a loop, and the sequence's time per scan in stages. Counters: median_ms_per_scan (wall), median_cpu_ms_per_scan (process CPU, all
/// threads), end_x_m (position of the last frame).
/// Build: link revisit_odometry, revisit_core, TBB, benchmark, and tests/odometry/synthetic_world.cpp.
#include "bench_main.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <tbb/global_control.h>

#include "core/se3.hpp"
#include "odometry/lidar_odometry.hpp"
#include "odometry/synthetic_world.hpp"
#include "pipeline/odometry_stages.hpp"

namespace revisit {
namespace {

std::filesystem::path KittiVelodyne() { return bench::DataDir() / "kitti00_first16" / "velodyne"; }

/// The 16 KITTI scans with the 0.205 degree correction, or nothing when the data is absent.
const std::vector<Scan>& KittiScans() {
    static const std::vector<Scan> scans = [] {
        std::vector<Scan> loaded;
        const auto dir = KittiVelodyne();
        for (int i = 0; i < 16; ++i) {
            char name[32];
            std::snprintf(name, sizeof(name), "%06d.bin", i);
            const auto file = dir / name;
            if (!std::filesystem::exists(file)) return std::vector<Scan>{};
            std::vector<float> raw(std::filesystem::file_size(file) / sizeof(float));
            std::FILE* f = std::fopen(file.c_str(), "rb");
            const std::size_t read = std::fread(raw.data(), sizeof(float), raw.size(), f);
            std::fclose(f);
            Scan scan;
            scan.index = static_cast<std::size_t>(i);
            const double angle = 0.205 * M_PI / 180.0;
            for (std::size_t k = 0; k + 3 < read; k += 4) {
                Eigen::Vector3d p(raw[k], raw[k + 1], raw[k + 2]);
                const Eigen::Vector3d axis = p.cross(Eigen::Vector3d::UnitZ());
                if (axis.norm() > 1e-9) p = Eigen::AngleAxisd(angle, axis.normalized()) * p;
                scan.points.push_back(p.cast<float>());
            }
            loaded.push_back(std::move(scan));
        }
        return loaded;
    }();
    return scans;
}

/// 16 simulated HDL-64E-like sweeps (64 beams x 2000 columns) of a drive at 0.86 m per sweep.
const std::vector<Scan>& SimulatedScans() {
    static const std::vector<Scan> scans = [] {
        Poses route;
        for (int i = 0; i < 16; ++i) {
            route.push_back(PoseFromXYZRPY(0.86 * i, 0.0, 1.73 + 0.03 * std::sin(1.3 * i), 0.005 * std::sin(0.9 * i),
                                           0.008 * std::sin(0.7 * i + 1.0), 0.0));
        }
        const auto world = test::MakeCity(route, 6.0, 3);
        const auto pattern = test::SpinningPattern(64, 2000, -24.8, 2.0, 120.0);
        std::vector<Scan> cast;
        for (int i = 0; i < 16; ++i) {
            cast.push_back(test::CastScan(world, pattern, [&](double) { return route[i]; }, 0.02, i));
            cast.back().index = static_cast<std::size_t>(i);
            cast.back().point_times.clear();
        }
        return cast;
    }();
    return scans;
}

/// Process CPU time [ms]: on a machine shared with other jobs, wall time measures the neighbours.
double CpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

void RunSequence(benchmark::State& state, const std::vector<Scan>& scans) {
    if (scans.empty()) {
        bench::SkipForMissingData(state, KittiVelodyne());
        return;
    }
    const int threads = static_cast<int>(state.range(0));
    OdometryConfig config;
    config.deskew = state.range(1) != 0;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<double> ms, cpu_ms;
    double end_x = 0.0;
    std::size_t points = 0;
    for (auto _ : state) {
        LidarOdometry odometry(config);
        for (const Scan& scan : scans) {
            const auto start = std::chrono::steady_clock::now();
            const double cpu_start = CpuMs();
            const Eigen::Isometry3d T = odometry.RegisterScan(scan);
            cpu_ms.push_back(CpuMs() - cpu_start);
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            end_x = T.translation().x();
            points += scan.points.size();
        }
    }
    std::sort(ms.begin(), ms.end());
    std::sort(cpu_ms.begin(), cpu_ms.end());
    state.counters["median_ms_per_scan"] = ms[ms.size() / 2];
    state.counters["median_cpu_ms_per_scan"] = cpu_ms[cpu_ms.size() / 2];
    state.counters["end_x_m"] = end_x;
    state.counters["points_per_scan"] = static_cast<double>(points) / static_cast<double>(ms.size());
}

/// The sequence as `revisit odometry` and `revisit run` register it (pipeline/odometry_stages.hpp: the
/// preparation of later scans runs ahead of the registrations): milliseconds per scan over the whole
/// sequence, which is what the overlap shortens (a scan's own latency does not). Arg: threads.
void RunStaged(benchmark::State& state, const std::vector<Scan>& loaded) {
    if (loaded.empty()) {
        bench::SkipForMissingData(state, KittiVelodyne());
        return;
    }
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<int>(state.range(0)));
    PipelineConfig settings;
    settings.input.follow_scene_scale = false;  // the default crop, as RunSequence
    std::vector<Scan> scans = loaded;  // moved through the stages and back each iteration
    std::vector<double> ms;
    double end_x = 0.0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        OdometryStages stages(settings);
        RunOdometryStages(stages, scans, [&](OdometryStages::Item&, const Eigen::Isometry3d& T_world_sensor) {
            end_x = T_world_sensor.translation().x();
        });
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
                     static_cast<double>(scans.size()));
    }
    std::sort(ms.begin(), ms.end());
    state.counters["median_ms_per_scan"] = ms[ms.size() / 2];
    state.counters["end_x_m"] = end_x;
}

void BM_OdometryKitti(benchmark::State& state) { RunSequence(state, KittiScans()); }
void BM_OdometryKittiStaged(benchmark::State& state) { RunStaged(state, KittiScans()); }
void BM_OdometrySimulated64(benchmark::State& state) { RunSequence(state, SimulatedScans()); }

// Args: threads, deskew.
BENCHMARK(BM_OdometryKitti)->Args({1, 0})->Args({2, 0})->Args({1, 1})->Args({2, 1})->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_OdometryKittiStaged)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->MinTime(3.0);
BENCHMARK(BM_OdometrySimulated64)->Args({1, 0})->Args({2, 0})->Unit(benchmark::kMillisecond)->MinTime(3.0);

}  // namespace
}  // namespace revisit

REVISIT_BENCHMARK_MAIN()
