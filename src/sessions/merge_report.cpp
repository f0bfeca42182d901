#include "sessions/merge_report.hpp"

#include "core/atomic_file.hpp"
#include "report/html_page.hpp"
#include "report/svg_plot.hpp"

namespace revisit {
namespace {

std::string Metres(const std::optional<double>& value) { return value ? FormatNumber(*value, 3) : "-"; }

/// One sessions-table row: a swatch in the session's sessions.svg colour, "NO" marked when unconnected.
std::string SessionRow(const MergeResult& result, std::size_t s) {
    const auto& session = result.sessions[s];
    const int in_session = int(session.state.NumAccepted());
    int cross = 0;
    for (const auto& c : result.cross) cross += c.accepted && (c.query_session == int(s) || c.ref_session == int(s));
    const bool connected = result.graph.connected[s] != 0;
    std::string row = "<tr><td><span style=\"display:inline-block;width:1em;height:1em;background:" + CssColor(SeriesColor(s)) +
                      "\"></span> " + std::to_string(s) + "</td>";
    row += connected ? "<td>yes</td>" : "<td style=\"color:#e11e1e;font-weight:bold\">NO</td>";
    for (const std::string& cell :
         {std::to_string(session.state.odometry.size()), std::to_string(session.state.maps.size()), std::to_string(in_session),
          std::to_string(cross), Metres(result.ape_common[s]), Metres(result.ape_aligned[s]), session.folder.string()})
        row += "<td>" + EscapeXml(cell) + "</td>";
    return row + "</tr>\n";
}

}  // namespace

std::string MergeReportHtml(const MergeResult& result) {
    HtmlPage page("revisit merge");
    page.Heading("Sessions in one frame")
        .Paragraph("The common frame is the odometry frame of session 0 (the anchor). A session is placed only when verified "
                   "cross-session closures tie it to the anchor; an unconnected session is listed, never drawn at the origin.")
        .Figure("sessions.svg", "The connected sessions' corrected trajectories in the common frame, one colour each; "
                                "cross-session closures as markers.");
    std::vector<std::string> rows;
    for (std::size_t s = 0; s < result.sessions.size(); ++s) rows.push_back(SessionRow(result, s));
    page.Heading("Sessions")
        .SortableTable({"session", "connected", "scans", "maps", "closures in-session", "cross", "APE common frame [m]",
                        "APE own alignment [m]", "run"},
                       rows)
        .Paragraph("APE columns need reference poses (a dataset's own or --gt).");
    page.Heading("Cross-session closures");
    if (result.cross.empty()) {
        page.Paragraph("No candidate reached the detector's inlier gate.");
    } else {
        std::vector<std::vector<std::string>> cross;
        for (const auto& c : result.cross) {
            cross.push_back({std::to_string(c.query_session) + " / " + std::to_string(c.closure.query_id),
                             std::to_string(c.ref_session) + " / " + std::to_string(c.closure.ref_id),
                             std::to_string(c.closure.num_inliers), FormatNumber(c.refinement.overlap, 2),
                             FormatNumber(c.refinement.rms, 3), c.accepted ? "yes" : "no", c.reason});
        }
        page.Table({"query session / map", "reference session / map", "inliers", "3D overlap", "RMS [m]", "accepted", "why not"},
                   cross);
    }
    page.Paragraph("Files: sessions.json, cross_closures.csv, session_KK_poses_{kitti,tum}.txt, map_joint.ply.");
    return page.Finish();
}

void WriteMergeReport(const std::filesystem::path& out, const MergeResult& result) {
    WriteFileAtomically(out / "index.html", MergeReportHtml(result));
}

}  // namespace revisit
