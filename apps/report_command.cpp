// scanloc report: a session's run folder as one self-contained HTML page with figures.

#include <iostream>

#include "commands.hpp"
#include "scanloc/report/html_report.hpp"
#include "scanloc/report/markup.hpp"

namespace scanloc::app {

void RegisterReportCommand(CLI::App& app) {
  struct Arguments {
    std::string run_dir;
    std::string iterations;
    ReportOptions options;
  };
  auto a = std::make_shared<Arguments>();
  IterationSelectionOptions& selection = a->options.selection;
  CLI::App* command = app.add_subcommand(
      "report", "write RUN_DIR/report.html: the session's figures and tables, for a browser");
  command->add_option("run_dir", a->run_dir, "run folder written by scanloc session --out")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->add_option("--out", a->options.output_path,
                      "page to write (default RUN_DIR/report.html)");
  command->add_option("--first", selection.first, "draw the first N localised iterations")
      ->capture_default_str();
  command
      ->add_option("--every", selection.every,
                   "draw one in every K localised iterations (0: K chosen to give about 12)")
      ->capture_default_str();
  command
      ->add_option("--flagged", selection.flagged,
                   "draw up to N flagged (not validated) iterations, evenly spread")
      ->capture_default_str();
  command->add_option("--iterations", a->iterations, "draw these too, e.g. 3,10-12,40");
  command
      ->add_option("--log", a->options.inputs.log_path,
                   "the session's sequence, when it is not where summary.json says")
      ->check(CLI::ExistingFile);
  command
      ->add_option("--line-map", a->options.inputs.line_map_path,
                   "the session's line map, when it is not where summary.json says")
      ->check(CLI::ExistingFile);
  command->final_callback([a] {
    if (!a->iterations.empty()) a->options.selection.indices = ParseIterationList(a->iterations);
    const ReportResult result = WriteRunReport(a->run_dir, a->options);
    for (const std::string& note : result.notes) std::cerr << "report: note: " << note << '\n';
    std::cout << "report: " << result.iterations << " iterations, " << result.drawn << " drawn ("
              << result.drawn_with_scan << " with their scans), " << FormatBytes(result.bytes)
              << "\n"
              << result.path << '\n';
  });
}

}  // namespace scanloc::app
