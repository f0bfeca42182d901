#include "pipeline/merge_report.hpp"

#include <cstdio>
#include <sstream>

#include "core/atomic_file.hpp"
#include "report/svg_plot.hpp"

namespace revisit {
namespace {

std::string Css(Rgb c) {
    char text[16];
    std::snprintf(text, sizeof(text), "#%02x%02x%02x", c.r, c.g, c.b);
    return text;
}

std::string Metres(const std::optional<double>& value) {
    if (!value) return "-";
    char text[32];
    std::snprintf(text, sizeof(text), "%.3f", *value);
    return text;
}

std::string Fixed(double value, const char* format) {
    char text[32];
    std::snprintf(text, sizeof(text), format, value);
    return text;
}

}  // namespace

std::string MergeReportHtml(const MergeResult& result) {
    std::ostringstream html;
    html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>revisit merge</title>\n"
         << "<style>body{font-family:sans-serif;margin:2em;color:#141414}table{border-collapse:collapse}"
            "td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}th{background:#f2f2f2}"
            "td.l{text-align:left}.swatch{display:inline-block;width:1em;height:1em;vertical-align:middle}"
            ".no{color:#e11e1e;font-weight:bold}</style></head><body>\n";
    html << "<h1>Sessions in one frame</h1>\n<p>The common frame is the odometry frame of session 0 (the anchor). "
            "A session is placed only when verified cross-session closures tie it to the anchor; an unconnected "
            "session is listed, never drawn at the origin.</p>\n";
    html << "<img src=\"sessions.svg\" alt=\"the connected sessions' corrected trajectories in the common frame, one "
            "colour each; cross-session closures as markers\">\n";
    html << "<h2>Sessions</h2>\n<table><tr><th>session</th><th>connected</th><th>scans</th><th>maps</th>"
            "<th>closures in-session</th><th>cross</th><th>APE common frame [m]</th><th>APE own alignment [m]</th>"
            "<th class=\"l\">run</th></tr>\n";
    for (std::size_t s = 0; s < result.sessions.size(); ++s) {
        const auto& session = result.sessions[s];
        int in_session = 0, cross = 0;
        for (const auto& record : session.state.closures) in_session += record.method == "density" && record.accepted;
        for (const auto& c : result.cross) cross += c.accepted && (c.query_session == int(s) || c.ref_session == int(s));
        const bool connected = result.graph.connected[s] != 0;
        html << "<tr><td><span class=\"swatch\" style=\"background:" << Css(SeriesColor(s)) << "\"></span> " << s << "</td><td"
             << (connected ? ">yes" : " class=\"no\">NO") << "</td><td>" << session.state.odometry.size() << "</td><td>"
             << session.state.maps.size() << "</td><td>" << in_session << "</td><td>" << cross << "</td><td>"
             << Metres(result.ape_common[s]) << "</td><td>" << Metres(result.ape_aligned[s]) << "</td><td class=\"l\">"
             << EscapeXml(session.folder.string()) << "</td></tr>\n";
    }
    html << "</table>\n<p>APE columns need reference poses (a dataset's own or <code>--gt</code>).</p>\n";
    html << "<h2>Cross-session closures</h2>\n";
    if (result.cross.empty()) html << "<p>No candidate reached the detector's inlier gate.</p>\n";
    else {
        html << "<table><tr><th>query session / map</th><th>reference session / map</th><th>inliers</th>"
                "<th>3D overlap</th><th>RMS [m]</th><th>accepted</th><th class=\"l\">why not</th></tr>\n";
        for (const auto& c : result.cross) {
            html << "<tr><td>" << c.query_session << " / " << c.closure.query_id << "</td><td>" << c.ref_session << " / "
                 << c.closure.ref_id << "</td><td>" << c.closure.num_inliers << "</td><td>"
                 << Fixed(c.refinement.overlap, "%.2f") << "</td><td>" << Fixed(c.refinement.rms, "%.3f") << "</td><td"
                 << (c.accepted ? ">yes" : " class=\"no\">no") << "</td><td class=\"l\">" << EscapeXml(c.reason) << "</td></tr>\n";
        }
        html << "</table>\n";
    }
    html << "<p>Files: <code>sessions.json</code>, <code>cross_closures.csv</code>, "
            "<code>session_KK_poses_{kitti,tum}.txt</code>, <code>map_joint.ply</code>.</p>\n</body></html>\n";
    return html.str();
}

void WriteMergeReport(const std::filesystem::path& out, const MergeResult& result) {
    WriteFileAtomically(out / "index.html", MergeReportHtml(result));
}

}  // namespace revisit
