#pragma once
/// Minimal SVG charts written in C++ (no scripts, no external fonts): line plots, bar charts, and a path
/// coloured by a value. Output is deterministic text.
#include "render/palette.hpp"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace revisit {

struct PlotSeries {
    std::string name;
    std::vector<double> x;
    std::vector<double> y;
    Rgb color;
    bool dashed = false;
};

struct PlotMarker {
    std::string label;
    double x = 0.0;
    double y = 0.0;
    Rgb color;
};

struct LinePlotSpec {
    std::string title;
    std::string x_label;
    std::string y_label;
    std::vector<PlotSeries> series;
    std::vector<PlotMarker> markers;           ///< drawn as circles with a label, e.g. max-F1 points
    std::optional<std::pair<double, double>> x_range;  ///< default: data range
    std::optional<std::pair<double, double>> y_range;
    int width = 640;   ///< [px]
    int height = 400;  ///< [px]
};

std::string LinePlotSvg(const LinePlotSpec& spec);

/// Horizontal bars, one per (label, value), value axis in `unit`.
std::string BarChartSvg(const std::string& title, const std::vector<std::pair<std::string, double>>& bars,
                        const std::string& unit, Rgb color, int width = 640);

/// A 2D path (x, y in metres, equal axes, north up) whose segments are coloured by `values` with a colour bar.
std::string ColoredPathSvg(const std::string& title, const std::vector<std::pair<double, double>>& xy,
                           const std::vector<double>& values, const std::string& value_label, int width = 640,
                           int height = 560);

/// Categorical colours for series (distinct, colour-blind friendly order).
Rgb SeriesColor(std::size_t index);

/// "#rrggbb", for SVG and CSS.
std::string CssColor(Rgb c);

/// Escapes &, <, >, " and ' for XML/HTML text and attributes.
std::string EscapeXml(const std::string& text);

}  // namespace revisit
