// Placeholder: replaced by the reference command.
#include "cli/commands.hpp"

namespace adrsph::cli {
Command register_reference(CLI::App& app) {
  auto* sub = app.add_subcommand("reference", "(not yet implemented)");
  return {sub, [] { return kExitBadInput; }};
}
}  // namespace adrsph::cli
