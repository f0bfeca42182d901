/// `revisit config`: the resolved configuration, commented, as a run would use it.
#include <iostream>

#include "commands.hpp"
#include "run_options.hpp"

namespace revisit::app {

void AddConfigCommand(CLI::App& root, Action& action) {
    auto o = std::make_shared<ConfigOptions>();
    auto* cmd = root.add_subcommand("config", "Print the resolved configuration (every parameter, unit and default)");
    cmd->footer(
        "The defaults, layered with --config files/presets and --set overrides, as YAML that --config reads.\n"
        "Examples:\n"
        "  revisit config > my.yaml\n"
        "  revisit config --config kitti --set density.resolution=0.2");
    AddConfigOptions(*cmd, *o);
    cmd->callback([o, &action] {
        action = [o] {
            std::cout << "# revisit configuration (revisit config)\n" << DumpConfig(ResolveConfig(*o));
            return 0;
        };
    });
}

}  // namespace revisit::app
