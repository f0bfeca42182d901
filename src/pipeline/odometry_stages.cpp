#include "pipeline/odometry_stages.hpp"

#include <chrono>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

namespace revisit {

OdometryStages::OdometryStages(const PipelineConfig& config)
    : odometry_(config.odometry), scene_scale_(config), ahead_(odometry_.config()) {}

void OdometryStages::Admit(Item& item) {
    item.position = admitted_++;
    item.settings = ahead_;
    // The scene scale looks at the raw scans in order; its change holds from the next scan on, so the
    // scans prepared ahead of the registration already get it (RegisterPrepared would redo them).
    item.update = scene_scale_.Add(item.position, item.scan);
    if (item.update) ahead_ = WithMaxRange(ahead_, item.update->to);
}

void OdometryStages::Prepare(Item& item) {
    const auto start = std::chrono::steady_clock::now();
    // Isolated: a thread waiting inside it never picks up another stage's work.
    tbb::this_task_arena::isolate([&] { item.prepared = PrepareScan(item.scan, item.settings); });
    item.prepare_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

Eigen::Isometry3d OdometryStages::Register(Item& item) {
    Eigen::Isometry3d T_world_sensor;
    tbb::this_task_arena::isolate([&] { T_world_sensor = odometry_.RegisterPrepared(item.scan, std::move(item.prepared)); });
    if (item.update) odometry_.SetMaxRange(item.update->to);
    return T_world_sensor;
}

void RunOdometryStages(OdometryStages& stages, const std::function<std::optional<Scan>()>& next,
                       const std::function<void(OdometryStages::Item&, const Eigen::Isometry3d&)>& registered) {
    using Item = OdometryStages::Item;
    std::optional<Scan> first = next();
    if (first && first->points.size() < kStagedMinPoints) {
        for (std::optional<Scan> scan = std::move(first); scan; scan = next()) {
            Item item;
            item.scan = std::move(*scan);
            stages.Admit(item);
            OdometryStages::Prepare(item);
            const Eigen::Isometry3d T_world_sensor = stages.Register(item);
            registered(item, T_world_sensor);
        }
        return;
    }
    tbb::parallel_pipeline(
        kOdometryScansInFlight,
        tbb::make_filter<void, Item>(tbb::filter_mode::serial_in_order,
                                     [&](tbb::flow_control& flow) {
                                         Item item;
                                         std::optional<Scan> scan = first ? std::move(first) : next();
                                         first.reset();
                                         if (!scan) {
                                             flow.stop();
                                             return item;
                                         }
                                         item.scan = std::move(*scan);
                                         stages.Admit(item);
                                         return item;
                                     }) &
            tbb::make_filter<Item, Item>(tbb::filter_mode::parallel,
                                         [](Item item) {
                                             OdometryStages::Prepare(item);
                                             return item;
                                         }) &
            tbb::make_filter<Item, void>(tbb::filter_mode::serial_in_order, [&](Item item) {
                const Eigen::Isometry3d T_world_sensor = stages.Register(item);
                registered(item, T_world_sensor);
            }));
}

void RunOdometryStages(OdometryStages& stages, std::vector<Scan>& scans,
                       const std::function<void(OdometryStages::Item&, const Eigen::Isometry3d&)>& registered) {
    std::size_t next = 0;
    RunOdometryStages(
        stages,
        [&]() -> std::optional<Scan> {
            if (next == scans.size()) return std::nullopt;
            return std::move(scans[next++]);
        },
        [&](OdometryStages::Item& item, const Eigen::Isometry3d& T_world_sensor) {
            registered(item, T_world_sensor);
            scans[item.position] = std::move(item.scan);
        });
}

}  // namespace revisit
