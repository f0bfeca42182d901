#pragma once
/// Summary statistics of an error distribution, as the `evo` tool reports them.
#include <cstddef>
#include <vector>

namespace revisit {

struct ErrorStatistics {
    std::size_t count = 0;
    double rmse = 0.0;
    double mean = 0.0;
    double median = 0.0;
    double std = 0.0;  ///< population standard deviation (ddof = 0), as numpy/evo
    double min = 0.0;
    double max = 0.0;
    double sse = 0.0;  ///< sum of squared errors
};

/// All fields 0 when `errors` is empty. The median of an even count is the mean of the middle two (numpy).
ErrorStatistics ComputeStatistics(std::vector<double> errors);

}  // namespace revisit
