#pragma once
/// The q-quantile of a sample, the value at index floor(q (n - 1)) of the sorted sample (no
/// interpolation; 0 for an empty sample). Takes its copy: the caller's order is kept.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace revisit {

inline double Quantile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    const auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return values[k];
}

}  // namespace revisit
