#pragma once
/// The report's SVG plots (issue 8, "Plots as SVG generated in C++").
#include "report/report_input.hpp"

#include <string>
#include <vector>

namespace revisit {

/// Precision (y) against recall (x) for every method, with each method's max-F1 point marked and labelled.
std::string PrCurvesSvg(const std::vector<PrCurve>& curves);

/// APE [m] over time [s], odometry (before) and corrected (after), in the trajectory colours of the pictures.
std::string ApeOverTimeSvg(const ErrorSeries& before, const ErrorSeries& after);

/// Top view of the corrected trajectory, each segment coloured by its APE (matched by nearest timestamp).
std::string TrajectoryApeSvg(const TimedTrajectory& trajectory, const ErrorSeries& ape);

/// Top view of the odometry trajectory; scans whose pose is only the motion prediction (degenerate or
/// diverged registration, RunState::odometry_fallbacks) in red.
std::string OdometryFallbacksSvg(const TimedTrajectory& odometry, const std::vector<std::size_t>& fallbacks);

/// Seconds per pipeline stage.
std::string TimingSvg(const std::vector<StageTiming>& timings);

}  // namespace revisit
