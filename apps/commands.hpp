#pragma once
// Each subcommand registers itself on the scanloc application.

#include <CLI/CLI.hpp>
#include <cmath>
#include <string>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc::app {

// Refuses a negative count or index: CLI11 would wrap "-1" into an unsigned option as 2^64 − 1.
inline CLI::Validator NonNegativeInteger() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        if (text.find('-') == std::string::npos) return "";
        return "expected an integer >= 0, got " + text;
      },
      "INT>=0");
}

// Refuses a coordinate that is not a finite number within ±1e6 m (kMaxCoordinateM).
inline CLI::Validator PlausibleCoordinate() {
  return CLI::Validator(
      [](const std::string& text) -> std::string {
        double value = 0.0;
        if (CLI::detail::lexical_cast(text, value) && std::abs(value) <= kMaxCoordinateM) return "";
        return "expected a finite number within ±1e6 (metres, radians), got " + text;
      },
      "|NUMBER|<=1e6");
}

void RegisterTestCommand(CLI::App& app);
void RegisterSimulateScanCommand(CLI::App& app);
void RegisterRefineCommand(CLI::App& app);
void RegisterSessionCommand(CLI::App& app);
void RegisterLocaliseCommand(CLI::App& app);
void RegisterEvaluateCommand(CLI::App& app);
void RegisterReportCommand(CLI::App& app);
void RegisterSimulateCommand(CLI::App& app);
void RegisterCompareCommand(CLI::App& app);
void RegisterOptionsCommand(CLI::App& app);
void RegisterExportGridCommand(CLI::App& app);

}  // namespace scanloc::app
