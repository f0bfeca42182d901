#pragma once
/// One benchmark run as a record: machine, suite, figures. Written to and read from JSON, printed as a
/// table, and compared with an earlier record as ratios (issue 10: judge a change by its ratio).
#include <filesystem>
#include <string>
#include <vector>

#include "bench_suite/machine.hpp"
#include "bench_suite/measure.hpp"

namespace revisit {

struct BenchRecord {
    std::string suite;  ///< "quick", "full", ...
    std::string started_utc;
    MachineInfo machine;
    double duration_s = 0.0;           ///< wall time of the whole suite
    std::size_t peak_memory_kb = 0;    ///< of the benchmark process at the end
    std::string data_dir;              ///< real data used, or "" when absent
    std::vector<std::string> skipped;  ///< cases not run, with the reason
    std::vector<Measurement> results;
};

std::string RecordToJson(const BenchRecord& record);
/// Throws DatasetError (naming `source`) on malformed JSON or missing fields.
BenchRecord RecordFromJson(const std::string& text, const std::string& source = "benchmark record");

void WriteRecord(const std::filesystem::path& file, const BenchRecord& record);
BenchRecord ReadRecord(const std::filesystem::path& file);

/// One figure measured in both records.
struct FigureRatio {
    std::string name;
    std::string unit;
    double old_median = 0.0;
    double new_median = 0.0;
    double ratio = 0.0;      ///< new / old
    double speedup = 0.0;    ///< > 1 when the new record is better (old/new for times, new/old for rates)
    double noise = 0.0;      ///< larger relative spread of the two [fraction]: ratios within 1 +- noise are noise
    bool same_setup = true;  ///< the notes (data, sizes, counts) agree; otherwise the ratio compares different work
    bool slower = false;     ///< worse beyond the runs' spread: every new sample is worse than every old one
};

struct Comparison {
    std::vector<FigureRatio> ratios;      ///< figures present in both, in the new record's order
    std::vector<std::string> only_old;    ///< names missing from the new record
    std::vector<std::string> only_new;    ///< names missing from the old record
    double geometric_mean_speedup = 1.0;  ///< over `ratios`
    std::vector<std::string> slower;      ///< figures with `slower` set, in order
};

Comparison CompareRecords(const BenchRecord& old_record, const BenchRecord& new_record);

/// One stage (the figure names' group before '/': odometry, tree, end_to_end, ...) against a reference.
struct StageRatio {
    std::string stage;
    int figures = 0;                      ///< figures of the stage measured in both records
    double geometric_mean_speedup = 1.0;  ///< > 1: the new record is faster than the reference
    std::string worst_figure;             ///< the figure with the lowest speedup
    double worst_speedup = 1.0;
    int slower = 0;                       ///< figures slower beyond the runs' spread
};

/// Per stage, in the order the stages first appear in `comparison`.
std::vector<StageRatio> StageRatios(const Comparison& comparison);

/// Human-readable tables (fixed-width, one figure per line).
std::string FormatRecord(const BenchRecord& record);
std::string FormatComparison(const Comparison& comparison);
std::string FormatStageRatios(const std::vector<StageRatio>& stages);

}  // namespace revisit
