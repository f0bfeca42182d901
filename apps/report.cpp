/// `revisit report RUN_DIR` and `revisit inspect RUN_DIR`: the HTML report from a run folder alone.
#include <algorithm>
#include <iostream>

#include "commands.hpp"
#include "pipeline/report_builder.hpp"
#include "report/report_writer.hpp"

namespace revisit::app {
namespace {
struct ReportOptions {
    std::string run;
    int closure = -1;
    std::vector<int> maps;
};

int RunReport(const ReportOptions& o) {
    const RunFolder run = RunFolder::Open(o.run);
    WriteRunReport(run, std::cerr);
    std::cout << run.report_index().string() << '\n';
    return 0;
}

int RunInspect(const ReportOptions& o) {
    const RunFolder run = RunFolder::Open(o.run);
    CheckRunDatabase(run);  // the pictures inspect draws are about the keypoints: no silent pages without them
    const ReportInput input = LoadReportInput(run);
    if (o.closure >= 0) {
        if (o.closure >= static_cast<int>(input.closures.size())) {
            std::cerr << "revisit: " << o.run << " has " << input.closures.size() << " closures (0 .. "
                      << static_cast<int>(input.closures.size()) - 1 << "); no closure " << o.closure << '\n';
            return 1;
        }
        std::cout << WriteClosurePage(input, static_cast<std::size_t>(o.closure), run.report_dir()).string() << '\n';
        return 0;
    }
    if (o.maps.size() != 2) {
        std::cerr << "revisit: inspect needs --closure N or --maps A B\n";
        return 1;
    }
    for (const int id : o.maps) {
        if (std::find(input.map_ids.begin(), input.map_ids.end(), id) == input.map_ids.end()) {
            std::cerr << "revisit: " << o.run << " has " << input.map_ids.size() << " local maps (0 .. "
                      << static_cast<int>(input.map_ids.size()) - 1 << "); no map " << id << '\n';
            return 1;
        }
    }
    std::cout << WriteMapPairPage(input, o.maps[0], o.maps[1], run.report_dir()).string() << '\n';
    return 0;
}
}  // namespace

void AddReportCommands(CLI::App& root, Action& action) {
    auto o = std::make_shared<ReportOptions>();
    auto* report = root.add_subcommand("report", "Regenerate the HTML report of a run folder");
    report->footer("Draws every picture from the run folder alone (nothing is recomputed).\nExample:\n  revisit report reports/latest");
    report->add_option("run", o->run, "run folder")->required();
    report->callback([o, &action] { action = [o] { return RunReport(*o); }; });

    auto* inspect = root.add_subcommand("inspect", "Render one closure, or any two local maps, side by side");
    inspect->footer(
        "--closure N: the page of closure N (its index in closures.csv among density-map closures).\n"
        "--maps A B: the same comparison for any two local maps at their odometry relative pose, to see why\n"
        "a closure was missed. Writes into RUN_DIR/report/ and prints the page's path.\n"
        "Examples:\n"
        "  revisit inspect reports/latest --closure 3\n"
        "  revisit inspect reports/latest --maps 41 2");
    inspect->add_option("run", o->run, "run folder")->required();
    auto* closure = inspect->add_option("--closure", o->closure, "closure index");
    auto* maps = inspect->add_option("--maps", o->maps, "two local map ids: query and reference")->expected(2);
    closure->excludes(maps);
    inspect->callback([o, &action] { action = [o] { return RunInspect(*o); }; });
}

}  // namespace revisit::app
