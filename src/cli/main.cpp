// adrsph: advection-diffusion-reaction SPH. Subcommands live in cmd_*.cpp.
#include <iostream>
#include <string>

#include "cli/commands.hpp"
#include "io/build_info.hpp"

int main(int argc, char** argv) {
  CLI::App app{"adrsph: advection-diffusion-reaction of a species with SPH"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("adrsph ") + adrsph::build_version() + " (" +
                                        adrsph::build_commit() + ")");
  const adrsph::cli::Command commands[] = {
      adrsph::cli::register_run(app), adrsph::cli::register_reference(app),
      adrsph::cli::register_compare(app), adrsph::cli::register_study(app),
      adrsph::cli::register_rtd(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : adrsph::cli::kExitBadInput;
  }
  for (const auto& cmd : commands)
    if (cmd.sub->parsed()) return cmd.action();
  return adrsph::cli::kExitBadInput;
}
