#pragma once
// Each subcommand registers itself on the scanloc application.

#include <CLI/CLI.hpp>

namespace scanloc::app {

void RegisterTestCommand(CLI::App& app);
void RegisterSimulateScanCommand(CLI::App& app);
void RegisterRefineCommand(CLI::App& app);
void RegisterSessionCommand(CLI::App& app);
void RegisterEvaluateCommand(CLI::App& app);
void RegisterReportCommand(CLI::App& app);
void RegisterSimulateCommand(CLI::App& app);
void RegisterCompareCommand(CLI::App& app);
void RegisterOptionsCommand(CLI::App& app);
void RegisterExportGridCommand(CLI::App& app);

}  // namespace scanloc::app
