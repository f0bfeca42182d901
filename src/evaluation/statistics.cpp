#include "evaluation/statistics.hpp"

#include <algorithm>
#include <cmath>

namespace revisit {

ErrorStatistics ComputeStatistics(std::vector<double> errors) {
    ErrorStatistics stats;
    stats.count = errors.size();
    if (errors.empty()) return stats;
    std::sort(errors.begin(), errors.end());
    const double n = static_cast<double>(errors.size());
    double sum = 0.0;
    for (const double e : errors) {
        sum += e;
        stats.sse += e * e;
    }
    stats.mean = sum / n;
    stats.rmse = std::sqrt(stats.sse / n);
    double squared_deviation = 0.0;
    for (const double e : errors) squared_deviation += (e - stats.mean) * (e - stats.mean);
    stats.std = std::sqrt(squared_deviation / n);
    stats.min = errors.front();
    stats.max = errors.back();
    const std::size_t half = errors.size() / 2;
    stats.median = errors.size() % 2 == 1 ? errors[half] : 0.5 * (errors[half - 1] + errors[half]);
    return stats;
}

}  // namespace revisit
