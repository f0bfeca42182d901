#include "bench_suite/measure.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace revisit {

Measurement Summarize(Measurement m) {
    if (m.samples.empty()) throw std::invalid_argument("benchmark '" + m.name + "': no samples");
    std::vector<double> sorted = m.samples;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    m.median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
    m.min = sorted.front();
    m.max = sorted.back();
    m.spread = m.median != 0.0 ? 0.5 * (m.max - m.min) / std::abs(m.median) : 0.0;
    return m;
}

namespace {
Measurement Collect(const std::string& name, const std::string& unit, FigureKind kind, const MeasureConfig& config,
                    const std::function<double()>& sample) {
    Measurement m;
    m.name = name;
    m.unit = unit;
    m.kind = kind;
    for (int i = 0; i < config.warmup; ++i) sample();
    for (int i = 0; i < std::max(1, config.repetitions); ++i) m.samples.push_back(sample());
    return Summarize(std::move(m));
}
}  // namespace

Measurement Measure(const std::string& name, const std::string& unit, FigureKind kind, const MeasureConfig& config,
                    const WorkFn& work) {
    return Collect(name, unit, kind, config, [&] {
        const auto start = std::chrono::steady_clock::now();
        const double items = work();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (kind == FigureKind::kItemsPerSecond) return ms > 0.0 ? items / (ms * 1e-3) : 0.0;
        return items > 0.0 ? ms / items : ms;
    });
}

Measurement MeasureValue(const std::string& name, const std::string& unit, FigureKind kind, const MeasureConfig& config,
                         const WorkFn& work) {
    return Collect(name, unit, kind, config, work);
}

}  // namespace revisit
