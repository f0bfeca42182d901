#pragma once
/// Each subcommand lives in its own file and registers itself on the root app.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace revisit::app {

/// What the chosen subcommand runs after parsing; returns the process exit code.
using Action = std::function<int()>;

void AddInfoCommand(CLI::App& root, Action& action);
void AddConvertCommand(CLI::App& root, Action& action);
void AddSimulateCommand(CLI::App& root, Action& action);
void AddRunCommand(CLI::App& root, Action& action);
void AddEvalCommand(CLI::App& root, Action& action);
void AddReportCommands(CLI::App& root, Action& action);
void AddOdometryCommand(CLI::App& root, Action& action);
void AddDemoCommand(CLI::App& root, Action& action);
void AddConfigCommand(CLI::App& root, Action& action);
void AddBenchCommand(CLI::App& root, Action& action);
void AddMergeCommand(CLI::App& root, Action& action);
void AddBatchCommand(CLI::App& root, Action& action);
void AddExportCommand(CLI::App& root, Action& action);

/// A progress line on stderr when it is a terminal, rewritten in place; silent otherwise.
void ShowProgress(const std::string& text);
void EndProgress();

}  // namespace revisit::app
