#pragma once
/// Facts about the machine and build a benchmark ran on, stored with every record.
#include <cstddef>
#include <string>

namespace revisit {

struct MachineInfo {
    unsigned cores = 0;      ///< std::thread::hardware_concurrency()
    int threads = 0;         ///< TBB threads allowed for this run (global_control or the default)
    std::string build_type;  ///< CMAKE_BUILD_TYPE of revisit_benchmark
    std::string compiler;
    std::string cpu;  ///< /proc/cpuinfo "model name" when readable
    std::string hostname;
    double load_average = 0.0;  ///< 1-minute load average when the run started (other jobs skew times)
};

MachineInfo CurrentMachine();

/// Peak resident memory of this process so far [KiB] (getrusage ru_maxrss).
std::size_t PeakMemoryKb();

/// Current UTC time, ISO 8601.
std::string UtcNow();

}  // namespace revisit
