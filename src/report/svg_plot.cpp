#include "report/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace revisit {
namespace {

constexpr int kLeft = 70, kRight = 20, kTop = 40, kBottom = 55;

std::string Num(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.2f", v);
    return text;
}

std::string Tick(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", std::abs(v) < 1e-12 ? 0.0 : v);
    return text;
}

double TickStep(double range) {
    const double raw = range / 5.0;
    const double power = std::pow(10.0, std::floor(std::log10(raw)));
    for (const double m : {1.0, 2.0, 5.0})
        if (m * power >= raw) return m * power;
    return 10.0 * power;
}

std::pair<double, double> Padded(std::pair<double, double> range) {
    if (!(range.second > range.first)) return {range.first - 0.5, range.first + 0.5};
    return range;
}

std::string Header(int width, int height, const std::string& title) {
    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
        << "\" viewBox=\"0 0 " << width << ' ' << height << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
        << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n"
        << "<text x=\"" << width / 2 << "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\" font-weight=\"bold\">"
        << EscapeXml(title) << "</text>\n";
    return svg.str();
}

}  // namespace

std::string EscapeXml(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (const char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string CssColor(Rgb c) {
    char text[8];
    std::snprintf(text, sizeof(text), "#%02x%02x%02x", c.r, c.g, c.b);
    return text;
}

Rgb SeriesColor(std::size_t index) {
    static constexpr std::array<Rgb, 8> kColors{Rgb{0, 114, 178}, Rgb{230, 159, 0}, Rgb{0, 158, 115},
                                                Rgb{204, 121, 167}, Rgb{86, 180, 233}, Rgb{213, 94, 0},
                                                Rgb{120, 120, 120}, Rgb{240, 228, 66}};
    return kColors[index % kColors.size()];
}

std::string LinePlotSvg(const LinePlotSpec& spec) {
    double x_min = std::numeric_limits<double>::infinity(), x_max = -x_min, y_min = x_min, y_max = -x_min;
    for (const auto& s : spec.series)
        for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
            x_min = std::min(x_min, s.x[i]), x_max = std::max(x_max, s.x[i]);
            y_min = std::min(y_min, s.y[i]), y_max = std::max(y_max, s.y[i]);
        }
    if (!std::isfinite(x_min)) x_min = 0, x_max = 1, y_min = 0, y_max = 1;
    const auto [x0, x1] = Padded(spec.x_range.value_or(std::pair{x_min, x_max}));
    const auto [y0, y1] = Padded(spec.y_range.value_or(std::pair{std::min(0.0, y_min), y_max}));
    const double plot_w = spec.width - kLeft - kRight, plot_h = spec.height - kTop - kBottom;
    const auto X = [&, x0 = x0, x1 = x1](double x) { return kLeft + (x - x0) / (x1 - x0) * plot_w; };
    const auto Y = [&, y0 = y0, y1 = y1](double y) { return kTop + (1.0 - (y - y0) / (y1 - y0)) * plot_h; };

    std::ostringstream svg;
    svg << Header(spec.width, spec.height, spec.title);
    // Grid and ticks.
    const double x_step = TickStep(x1 - x0), y_step = TickStep(y1 - y0);
    for (double t = std::ceil(x0 / x_step) * x_step; t <= x1 + 1e-9 * x_step; t += x_step)
        svg << "<line x1=\"" << Num(X(t)) << "\" y1=\"" << kTop << "\" x2=\"" << Num(X(t)) << "\" y2=\"" << kTop + plot_h
            << "\" stroke=\"#e5e5e5\"/><text x=\"" << Num(X(t)) << "\" y=\"" << Num(kTop + plot_h + 16)
            << "\" text-anchor=\"middle\">" << Tick(t) << "</text>\n";
    for (double t = std::ceil(y0 / y_step) * y_step; t <= y1 + 1e-9 * y_step; t += y_step)
        svg << "<line x1=\"" << kLeft << "\" y1=\"" << Num(Y(t)) << "\" x2=\"" << Num(kLeft + plot_w) << "\" y2=\""
            << Num(Y(t)) << "\" stroke=\"#e5e5e5\"/><text x=\"" << kLeft - 6 << "\" y=\"" << Num(Y(t) + 4)
            << "\" text-anchor=\"end\">" << Tick(t) << "</text>\n";
    svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << Num(plot_w) << "\" height=\"" << Num(plot_h)
        << "\" fill=\"none\" stroke=\"#444\"/>\n";
    svg << "<text x=\"" << Num(kLeft + plot_w / 2) << "\" y=\"" << spec.height - 12 << "\" text-anchor=\"middle\">"
        << EscapeXml(spec.x_label) << "</text>\n";
    svg << "<text transform=\"translate(16," << Num(kTop + plot_h / 2) << ") rotate(-90)\" text-anchor=\"middle\">"
        << EscapeXml(spec.y_label) << "</text>\n";
    // Series, clipped to the plot area.
    svg << "<clipPath id=\"plot\"><rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << Num(plot_w)
        << "\" height=\"" << Num(plot_h) << "\"/></clipPath>\n<g clip-path=\"url(#plot)\">\n";
    for (const auto& s : spec.series) {
        svg << "<polyline fill=\"none\" stroke-width=\"2\" stroke=\"" << CssColor(s.color) << '"'
            << (s.dashed ? " stroke-dasharray=\"6 4\"" : "") << " points=\"";
        for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
            if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) svg << Num(X(s.x[i])) << ',' << Num(Y(s.y[i])) << ' ';
        svg << "\"/>\n";
    }
    svg << "</g>\n";
    for (const auto& m : spec.markers)
        svg << "<circle cx=\"" << Num(X(m.x)) << "\" cy=\"" << Num(Y(m.y)) << "\" r=\"5\" fill=\"" << CssColor(m.color)
            << "\" stroke=\"#000\"/>"
            << (m.label.empty() ? std::string()
                                : "<text x=\"" + Num(X(m.x) + 8) + "\" y=\"" + Num(Y(m.y) - 8) + "\">" + EscapeXml(m.label) + "</text>")
            << "\n";
    // Legend, top right inside the plot.
    for (std::size_t i = 0; i < spec.series.size(); ++i) {
        const double y = kTop + 14 + 18.0 * i, x = kLeft + plot_w - 250;
        svg << "<line x1=\"" << Num(x) << "\" y1=\"" << Num(y) << "\" x2=\"" << Num(x + 24) << "\" y2=\"" << Num(y)
            << "\" stroke-width=\"3\" stroke=\"" << CssColor(spec.series[i].color) << '"'
            << (spec.series[i].dashed ? " stroke-dasharray=\"6 4\"" : "") << "/><text x=\"" << Num(x + 30) << "\" y=\""
            << Num(y + 4) << "\">" << EscapeXml(spec.series[i].name) << "</text>\n";
    }
    svg << "</svg>\n";
    return svg.str();
}

std::string BarChartSvg(const std::string& title, const std::vector<std::pair<std::string, double>>& bars,
                        const std::string& unit, Rgb color, int width) {
    const int label_w = 170, row = 26;
    const int height = kTop + row * static_cast<int>(bars.size()) + 45;
    double max_value = 0.0;
    for (const auto& bar : bars) max_value = std::max(max_value, bar.second);
    if (!(max_value > 0.0)) max_value = 1.0;
    const double plot_w = width - label_w - 90;
    std::ostringstream svg;
    svg << Header(width, height, title);
    for (std::size_t i = 0; i < bars.size(); ++i) {
        const double y = kTop + row * static_cast<double>(i);
        const double w = std::max(0.0, bars[i].second) / max_value * plot_w;
        svg << "<text x=\"" << label_w - 8 << "\" y=\"" << Num(y + 17) << "\" text-anchor=\"end\">"
            << EscapeXml(bars[i].first) << "</text><rect x=\"" << label_w << "\" y=\"" << Num(y + 4) << "\" width=\""
            << Num(w) << "\" height=\"" << row - 8 << "\" fill=\"" << CssColor(color) << "\"/><text x=\""
            << Num(label_w + w + 6) << "\" y=\"" << Num(y + 17) << "\">" << Tick(std::round(bars[i].second * 1000) / 1000)
            << ' ' << EscapeXml(unit) << "</text>\n";
    }
    svg << "<line x1=\"" << label_w << "\" y1=\"" << kTop << "\" x2=\"" << label_w << "\" y2=\"" << height - 45
        << "\" stroke=\"#444\"/>\n</svg>\n";
    return svg.str();
}

std::string ColoredPathSvg(const std::string& title, const std::vector<std::pair<double, double>>& xy,
                           const std::vector<double>& values, const std::string& value_label, int width, int height) {
    std::ostringstream svg;
    svg << Header(width, height, title);
    const std::size_t n = std::min(xy.size(), values.size());
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300, v_max = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        x0 = std::min(x0, xy[i].first), x1 = std::max(x1, xy[i].first);
        y0 = std::min(y0, xy[i].second), y1 = std::max(y1, xy[i].second);
        if (std::isfinite(values[i])) v_max = std::max(v_max, values[i]);
    }
    if (n < 2) return svg.str() + "<text x=\"20\" y=\"60\">no data</text>\n</svg>\n";
    if (!(v_max > 0.0)) v_max = 1.0;
    const double bar_w = 80, plot_w = width - 40 - bar_w, plot_h = height - kTop - 40;
    const double scale = std::min(plot_w / std::max(x1 - x0, 1e-6), plot_h / std::max(y1 - y0, 1e-6));
    const auto X = [&](double x) { return 20 + (x - x0) * scale; };
    const auto Y = [&](double y) { return kTop + plot_h - (y - y0) * scale; };  // north up, equal axes
    // Value -> colour: blue (low) to red (high) through yellow.
    const auto ramp = [](double t) {
        t = std::clamp(t, 0.0, 1.0);
        const Rgb low{40, 80, 200}, mid{240, 200, 40}, high{200, 20, 20};
        const Rgb a = t < 0.5 ? low : mid, b = t < 0.5 ? mid : high;
        const double f = t < 0.5 ? 2 * t : 2 * t - 1;
        const auto mix = [f](int p, int q) { return static_cast<std::uint8_t>(std::lround(p + f * (q - p))); };
        return Rgb{mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
    };
    for (std::size_t i = 0; i + 1 < n; ++i)
        svg << "<line x1=\"" << Num(X(xy[i].first)) << "\" y1=\"" << Num(Y(xy[i].second)) << "\" x2=\""
            << Num(X(xy[i + 1].first)) << "\" y2=\"" << Num(Y(xy[i + 1].second)) << "\" stroke-width=\"3\" stroke=\""
            << CssColor(ramp(values[i] / v_max)) << "\"/>\n";
    // Colour bar with its scale; a 1-2-5 scale bar in metres below the path.
    const double bx = width - bar_w + 10;
    for (int k = 0; k < 50; ++k)
        svg << "<rect x=\"" << Num(bx) << "\" y=\"" << Num(kTop + plot_h * (1.0 - (k + 1) / 50.0)) << "\" width=\"16\" height=\""
            << Num(plot_h / 50.0 + 0.5) << "\" fill=\"" << CssColor(ramp((k + 0.5) / 50.0)) << "\"/>\n";
    svg << "<text x=\"" << Num(bx + 20) << "\" y=\"" << kTop + 10 << "\">" << Tick(std::round(v_max * 100) / 100)
        << "</text><text x=\"" << Num(bx + 20) << "\" y=\"" << Num(kTop + plot_h) << "\">0</text>\n"
        << "<text x=\"" << Num(bx) << "\" y=\"" << Num(kTop + plot_h + 18) << "\">" << EscapeXml(value_label) << "</text>\n";
    const double bar_m = TickStep((x1 - x0) / 1.5);
    svg << "<line x1=\"20\" y1=\"" << height - 15 << "\" x2=\"" << Num(20 + bar_m * scale) << "\" y2=\"" << height - 15
        << "\" stroke=\"#000\" stroke-width=\"3\"/><text x=\"20\" y=\"" << height - 21 << "\">" << Tick(bar_m)
        << " m</text>\n</svg>\n";
    return svg.str();
}

}  // namespace revisit
