// The subcommands of the `impactlab` program, one function each; each is
// defined in cli/<name>_command.cpp.
#pragma once

#include "command.hpp"

namespace impactlab::cli {

Command add_bench_command(CLI::App& app);
Command add_scenes_command(CLI::App& app);
Command add_simulate_command(CLI::App& app);
Command add_reproduce_command(CLI::App& app);
Command add_compare_command(CLI::App& app);
Command add_poincare_command(CLI::App& app);
Command add_sweep_command(CLI::App& app);
Command add_basins_command(CLI::App& app);  // in sweep_command.cpp: a sweep
Command add_attractors_command(CLI::App& app);  // in sweep_command.cpp: a sweep
Command add_periodic_command(CLI::App& app);
Command add_spectrum_command(CLI::App& app);
Command add_continue_command(CLI::App& app);
Command add_explore_command(CLI::App& app);

}  // namespace impactlab::cli
