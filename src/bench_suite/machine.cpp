#include "bench_suite/machine.hpp"

#include <sys/resource.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <cstdlib>
#include <ctime>
#include <fstream>
#include <thread>

#ifndef REVISIT_BUILD_TYPE
#define REVISIT_BUILD_TYPE "unknown"
#endif

namespace revisit {

namespace {
std::string CpuModel() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);) {
        if (line.rfind("model name", 0) != 0) continue;
        const auto colon = line.find(':');
        if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
    return "";
}
}  // namespace

MachineInfo CurrentMachine() {
    MachineInfo info;
    info.cores = std::thread::hardware_concurrency();
    info.threads = static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    info.build_type = REVISIT_BUILD_TYPE;
    info.build_type = info.build_type.empty() ? "unspecified" : info.build_type;
#if defined(__clang__)
    info.compiler = "clang " __clang_version__;
#elif defined(__GNUC__)
    info.compiler = "gcc " __VERSION__;
#endif
    info.cpu = CpuModel();
    char host[256] = {};
    if (gethostname(host, sizeof(host) - 1) == 0) info.hostname = host;
    double load[1] = {0.0};
    if (getloadavg(load, 1) == 1) info.load_average = load[0];
    return info;
}

std::size_t PeakMemoryKb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<std::size_t>(usage.ru_maxrss);
}

std::string UtcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

}  // namespace revisit
