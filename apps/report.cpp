/// `revisit report RUN_DIR` and `revisit inspect RUN_DIR`: the HTML report from a run folder alone.
#include <algorithm>
#include <iostream>

#include "commands.hpp"
#include "core/owned_files.hpp"
#include "pipeline/interrupt.hpp"
#include "pipeline/report_builder.hpp"
#include "report/report_writer.hpp"
#include "run_options.hpp"

namespace revisit::app {
namespace {
struct ReportOptions {
    std::string run;
    int closure = -1;
    int map = -1;
    std::vector<int> maps;
    std::vector<std::string> overrides;
    int threads = 0;
    bool quiet = false;
};

int RunReport(const ReportOptions& o) {
    const auto threads = LimitThreads(o.threads);
    const RunFolder run = RunFolder::Open(o.run);
    InstallInterruptHandler();
    try {
        WriteRunReport(run, std::cerr, {o.quiet, o.overrides});
    } catch (const Interrupted&) {
        std::cerr << "revisit: interrupted; the previous report in " << run.report_dir().string() << " is kept as it was\n";
        return 130;
    }
    std::cout << run.report_index().string() << '\n';
    return 0;
}

int RunInspect(const ReportOptions& o) {
    const RunFolder run = RunFolder::Open(o.run);
    RefuseLinkedFolder(run.report_dir());  // the pages go into the run folder, not where a link points
    CheckRunDatabase(run);  // the pictures inspect draws are about the keypoints: no silent pages without them
    const ReportInput input = LoadReportInput(run);
    const ReportConfig config = RunReportConfig(run, {});
    if (o.closure >= 0) {
        if (o.closure >= static_cast<int>(input.closures.size())) {
            std::cerr << "revisit: " << o.run << " has " << input.closures.size() << " closures (0 .. "
                      << static_cast<int>(input.closures.size()) - 1 << "); no closure " << o.closure << '\n';
            return 1;
        }
        std::cout << WriteClosurePage(input, static_cast<std::size_t>(o.closure), run.report_dir(), config).string() << '\n';
        return 0;
    }
    if (o.map >= 0) {
        // An unknown id throws std::out_of_range naming the run's map count.
        std::cout << WriteSingleMapPage(input, o.map, run.report_dir(), config).string() << '\n';
        return 0;
    }
    if (o.maps.size() != 2) {
        std::cerr << "revisit: inspect needs --closure N, --map N or --maps A B\n";
        return 1;
    }
    for (const int id : o.maps) {
        if (std::find(input.map_ids.begin(), input.map_ids.end(), id) == input.map_ids.end()) {
            std::cerr << "revisit: " << o.run << " has " << input.map_ids.size() << " local maps (0 .. "
                      << static_cast<int>(input.map_ids.size()) - 1 << "); no map " << id << '\n';
            return 1;
        }
    }
    std::cout << WriteMapPairPage(input, o.maps[0], o.maps[1], run.report_dir(), config).string() << '\n';
    return 0;
}
}  // namespace

void AddReportCommands(CLI::App& root, Action& action) {
    auto o = std::make_shared<ReportOptions>();
    auto* report = root.add_subcommand("report", "Regenerate the HTML report of a run folder");
    report->footer(
        "Draws every picture from the run folder alone (nothing is recomputed); replaces the pages in RUN_DIR/report/.\n"
        "Pages for the closures that reached the acceptance threshold (all of them up to output.report_closure_pages,\n"
        "else every false one, the worst, the best and a sample), the output.report_candidates strongest below it and\n"
        "at most output.report_map_pages of their maps: the report's size does not grow with the sequence. Every\n"
        "candidate and map is a row of the index's tables (`revisit inspect` renders the others). Templates and\n"
        "style: share/report/ (REVISIT_SHARE_DIR overrides).\n"
        "Examples:\n"
        "  revisit report reports/latest\n"
        "  revisit report reports/latest --set output.report_candidates=100 --threads 2");
    report->add_option("run", o->run, "run folder")->required();
    report->add_option("--set", o->overrides, "key=value over the run's configuration (output.report_closure_pages, output.report_candidates, output.report_map_pages)");
    report->add_option("--threads", o->threads, "pages rendered in parallel (default: all cores; the files do not depend on it)");
    report->add_flag("--quiet", o->quiet, "no progress output");
    report->callback([o, &action] { action = [o] { return RunReport(*o); }; });

    auto* inspect = root.add_subcommand("inspect", "Render one closure, one local map, or any two local maps side by side");
    inspect->footer(
        "--closure N: the page of closure candidate N (its index in closures.csv among density-map closures; the\n"
        "report's table lists every one).\n"
        "--map N: the page of local map N.\n"
        "--maps A B: the same comparison for any two local maps at their odometry relative pose, to see why\n"
        "a closure was missed. Writes into RUN_DIR/report/ and prints the page's path.\n"
        "Examples:\n"
        "  revisit inspect reports/latest --closure 3\n"
        "  revisit inspect reports/latest --map 12\n"
        "  revisit inspect reports/latest --maps 41 2");
    inspect->add_option("run", o->run, "run folder")->required();
    auto* closure = inspect->add_option("--closure", o->closure, "closure index");
    auto* map = inspect->add_option("--map", o->map, "local map id");
    auto* maps = inspect->add_option("--maps", o->maps, "two local map ids: query and reference")->expected(2);
    closure->excludes(maps);
    closure->excludes(map);
    map->excludes(maps);
    inspect->callback([o, &action] { action = [o] { return RunInspect(*o); }; });
}

}  // namespace revisit::app
