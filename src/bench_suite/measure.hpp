#pragma once
/// The benchmark harness: run a piece of work after a warm-up, repeatedly, and summarise the samples
/// (median, min, max, spread) so one figure can be compared across runs and machines (issue 10).
#include <functional>
#include <string>
#include <vector>

namespace revisit {

enum class FigureKind {
    kMsPerItem,       ///< time per item: lower is better ("ms/scan", "ms/map")
    kItemsPerSecond,  ///< throughput: higher is better ("scans/s", "MB/s")
    kAbsolute,        ///< a value reported by the work itself (e.g. peak memory [MiB]), lower is better
};

struct Measurement {
    std::string name;  ///< "group/case", unique within a suite
    std::string unit;  ///< "ms/scan", "MB/s", "MiB", ...
    FigureKind kind = FigureKind::kMsPerItem;
    std::vector<double> samples;  ///< one per repetition, in `unit`
    double median = 0.0;
    double min = 0.0;
    double max = 0.0;
    double spread = 0.0;  ///< (max - min) / 2 / median: half the relative range [fraction]
    std::string note;     ///< data and parameters of the case

    bool higher_is_better() const { return kind == FigureKind::kItemsPerSecond; }
};

struct MeasureConfig {
    int warmup = 1;       ///< untimed runs before the samples (caches, lazy allocations, page faults)
    int repetitions = 5;  ///< timed runs
};

/// Fills median/min/max/spread from `samples` (which must not be empty).
Measurement Summarize(Measurement measurement);

/// One run of the work; returns how many items it processed (scans, maps, bytes in MB, ...).
using WorkFn = std::function<double()>;

/// Times `work` `repetitions` times after `warmup` untimed runs; each sample is wall milliseconds per
/// item (kMsPerItem) or items per second (kItemsPerSecond).
Measurement Measure(const std::string& name, const std::string& unit, FigureKind kind, const MeasureConfig& config,
                    const WorkFn& work);

/// A figure the work reports itself, one value per run (`kind` is usually kAbsolute).
Measurement MeasureValue(const std::string& name, const std::string& unit, FigureKind kind, const MeasureConfig& config,
                         const WorkFn& work);

}  // namespace revisit
