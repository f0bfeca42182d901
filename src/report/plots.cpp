#include "report/plots.hpp"

#include "report/svg_plot.hpp"

#include <algorithm>
#include <cstdio>

namespace revisit {

std::string PrCurvesSvg(const std::vector<PrCurve>& curves) {
    LinePlotSpec spec;
    spec.title = "Precision-recall (dots: max F1)";
    spec.x_label = "recall";
    spec.y_label = "precision";
    spec.x_range = {0.0, 1.0};
    spec.y_range = {0.0, 1.02};
    for (std::size_t i = 0; i < curves.size(); ++i) {
        // The max-F1 value goes into the legend, not beside its dot: dots of several methods lie close together.
        const PrCurvePoint best = MaxF1(curves[i]);
        char label[96];
        std::snprintf(label, sizeof(label), " (max F1 %.3f)", best.F1());
        PlotSeries series{curves[i].method + label, {}, {}, SeriesColor(i)};
        auto points = curves[i].points;
        std::stable_sort(points.begin(), points.end(), [](const PrCurvePoint& a, const PrCurvePoint& b) { return a.recall < b.recall; });
        for (const auto& p : points) {
            series.x.push_back(p.recall);
            series.y.push_back(p.precision);
        }
        spec.series.push_back(std::move(series));
        spec.markers.push_back({"", best.recall, best.precision, SeriesColor(i)});
    }
    return LinePlotSvg(spec);
}

std::string ApeOverTimeSvg(const ErrorSeries& before, const ErrorSeries& after) {
    LinePlotSpec spec;
    spec.title = "Absolute pose error over time";
    spec.x_label = "time [s]";
    spec.y_label = "APE [m]";
    spec.series.push_back({"odometry (before)", before.timestamps, before.values, palette::kOdometry});
    spec.series.push_back({"corrected (after)", after.timestamps, after.values, palette::kCorrected});
    return LinePlotSvg(spec);
}

std::string TrajectoryApeSvg(const TimedTrajectory& trajectory, const ErrorSeries& ape) {
    std::vector<std::pair<double, double>> xy;
    std::vector<double> values;
    std::size_t j = 0;
    for (std::size_t i = 0; i < trajectory.T_world_sensor.size(); ++i) {
        const double t = i < trajectory.timestamps.size() ? trajectory.timestamps[i] : double(i);
        // Both series are sorted by time: advance to the nearest error sample.
        while (j + 1 < ape.timestamps.size() && std::abs(ape.timestamps[j + 1] - t) <= std::abs(ape.timestamps[j] - t)) ++j;
        if (j >= ape.values.size()) break;
        const auto& p = trajectory.T_world_sensor[i].translation();
        xy.emplace_back(p.x(), p.y());
        values.push_back(ape.values[j]);
    }
    return ColoredPathSvg("Corrected trajectory coloured by APE", xy, values, "APE [m]");
}

std::string OdometryFallbacksSvg(const TimedTrajectory& odometry, const std::vector<std::size_t>& fallbacks) {
    std::vector<std::pair<double, double>> xy;
    std::vector<double> values(odometry.T_world_sensor.size(), 0.0);
    for (const auto& T : odometry.T_world_sensor) xy.emplace_back(T.translation().x(), T.translation().y());
    for (const std::size_t i : fallbacks) {
        if (i < values.size()) values[i] = 1.0;
    }
    return ColoredPathSvg("Odometry trajectory: motion predictions (no registration) at 1", xy, values, "fallback");
}

std::string TimingSvg(const std::vector<StageTiming>& timings) {
    std::vector<std::pair<std::string, double>> bars;
    for (const auto& t : timings) bars.emplace_back(t.stage, t.seconds);
    return BarChartSvg("Time per stage", bars, "s", {0, 114, 178});
}

}  // namespace revisit
