/// `revisit config`: the resolved configuration, commented, as a run would use it.
#include <iostream>

#include "commands.hpp"
#include "run_options.hpp"

namespace revisit::app {

void AddConfigCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<ConfigOptions>();
    auto dataset = std::make_shared<std::string>();
    auto* cmd = root.add_subcommand("config", "Print the resolved configuration (every parameter, unit and default)");
    cmd->footer(
        "The defaults, layered with --config files/presets and --set overrides, as YAML that --config reads.\n"
        "Examples:\n"
        "  revisit config > my.yaml\n"
        "  revisit config --config kitti --set density.resolution=0.2\n"
        "  revisit config --dataset ~/walk    (also the settings derived from its first scans, and why)");
    AddConfigOptions(*cmd, *o);
    cmd->add_option("--dataset", *dataset, "derive the settings no --config/--set gives from this dataset, as `run` does");
    cmd->callback([o, dataset, &action] {
        action = [o, dataset] {
            const PipelineConfig config = dataset->empty() ? ResolveConfig(*o) : ResolveConfigFor(*o, *dataset, std::cerr);
            std::cout << "# revisit configuration (revisit config)\n";
            for (const auto& line : config.derived) std::cout << "# derived from the data: " << line << '\n';
            std::cout << DumpConfig(config);
            return 0;
        };
    });
}

}  // namespace revisit::app
