// Placeholder: replaced by the compare command.
#include "cli/commands.hpp"

namespace adrsph::cli {
Command register_compare(CLI::App& app) {
  auto* sub = app.add_subcommand("compare", "(not yet implemented)");
  return {sub, [] { return kExitBadInput; }};
}
}  // namespace adrsph::cli
