// scanloc options: every key of the JSON config (--config) and of --set, with its default, the
// values it accepts and its meaning.

#include <iostream>

#include "commands.hpp"
#include "scanloc/config/config.hpp"

namespace scanloc::app {

void RegisterOptionsCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "options", "list every option of --config files and --set: key, default, range, meaning");
  command->final_callback([] { std::cout << OptionsHelp(); });
}

}  // namespace scanloc::app
