// Placeholder: replaced by the run command.
#include "cli/commands.hpp"

namespace adrsph::cli {
Command register_run(CLI::App& app) {
  auto* sub = app.add_subcommand("run", "(not yet implemented)");
  return {sub, [] { return kExitBadInput; }};
}
}  // namespace adrsph::cli
