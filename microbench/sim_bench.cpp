/// Simulator speed: rays per second of the ray caster (1 and 2 threads) and the time of a
/// 64-beam sequence (100 scans of the demo route, written nowhere; x10 for 1,000 scans).
#include "bench_main.hpp"
#include <tbb/global_control.h>

#include "sim/presets.hpp"
#include "sim/scan_simulator.hpp"

namespace revisit {
namespace {

const SimPlan& DemoPlan() {
    static const SimPlan plan = PlanSimulation(SimPreset("demo"));
    return plan;
}

/// One 64-beam sweep (131,072 rays) per iteration at poses spread along the demo route.
void BM_RayCastHdl64(benchmark::State& state) {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
    const SimPlan& plan = DemoPlan();
    const RayCaster caster(plan.world);
    const SensorConfig sensor = Hdl64Sensor();
    const auto rays = MakeRays(sensor, 0);
    std::size_t k = 0, points = 0;
    for (auto _ : state) {
        const std::size_t index = (k++ * 97) % plan.trajectory.size();
        SweepInput sweep;
        sweep.index = index;
        sweep.timestamp = plan.trajectory.timestamps[index];
        sweep.T_world_sensor = plan.trajectory.poses[index];
        sweep.T_world_sensor_start = sweep.T_world_sensor;
        const Scan scan = SimulateScan(caster, sensor, rays, sweep, 1);
        points += scan.points.size();
        benchmark::DoNotOptimize(scan.points.data());
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * rays.size()));
    state.counters["points_per_scan"] = static_cast<double>(points) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_RayCastHdl64)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

class NullWriter : public DatasetWriter {
  public:
    void Write(const Scan& scan) override { benchmark::DoNotOptimize(scan.points.data()); }
    void Finish() override {}
};

/// 100 scans of the demo sequence end to end (plan, moving cars, odometry prior), 2 threads.
void BM_Sequence100ScansHdl64(benchmark::State& state) {
    SimConfig config = SimPreset("demo");
    config.max_scans = 100;
    for (auto _ : state) {
        NullWriter writer;
        const SimSummary summary = SimulateSequence(config, writer);
        benchmark::DoNotOptimize(summary.points);
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * 100));
}
BENCHMARK(BM_Sequence100ScansHdl64)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace revisit

REVISIT_BENCHMARK_MAIN()
