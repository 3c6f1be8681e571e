// The `impactlab` program: parses and validates the command line, calls the
// library, writes the outputs. Exit status: 0 done; 2 bad input (one line on
// stderr naming the key and the value); 3 the run stopped early on a physical
// diagnostic (Painlevé, no progress) — its outputs are complete and say so;
// 1 anything else.
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/command.hpp"
#include "cli/commands.hpp"
#include "io/bad_input.hpp"

int main(int argc, char** argv) {
  using namespace impactlab::cli;
  CLI::App app{"impactlab: event-driven simulation of impact oscillators", "impactlab"};
  app.set_version_flag("--version", std::string("impactlab ") + IMPACTLAB_VERSION);
  app.require_subcommand(1);

  const std::vector<Command> commands = {
      add_scenes_command(app),
      add_simulate_command(app),
      add_reproduce_command(app),
      add_compare_command(app),
      add_bench_command(app),
      add_poincare_command(app),
      add_sweep_command(app),
      add_basins_command(app),
      add_periodic_command(app),
      add_spectrum_command(app),
      add_continue_command(app),
  };

  const std::vector<std::string> command_line(argv, argv + argc);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& success) {
    return app.exit(success);
  } catch (const CLI::ParseError& error) {
    std::cerr << "impactlab: " << error.what() << '\n';
    return exit_bad_input;
  }

  try {
    for (const auto& command : commands)
      if (command.app->parsed()) return command.run(command_line);
  } catch (const impactlab::BadInput& bad) {
    std::cerr << "impactlab: " << bad.what() << '\n';
    return exit_bad_input;
  } catch (const std::exception& error) {
    std::cerr << "impactlab: error: " << error.what() << '\n';
    return exit_failed;
  }
  return exit_done;
}
