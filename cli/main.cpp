// The `impactlab` program: parses and validates the command line, calls the
// library, writes the outputs. Exit status: 0 done; 2 bad input (one line on
// stderr naming the key and the value); 3 the run stopped early on a physical
// diagnostic (Painlevé, no progress, frozen time, non-finite state, step
// budget) or a numerical library's refusal — its outputs are complete and say
// so; 4 an output that cannot be written (a read-only folder, a full disk: one
// line naming the file and the system's reason, nothing half-written left);
// 1 anything else.
#include <csignal>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <boost/math/policies/error_handling.hpp>
#include <gsl/gsl_errno.h>

#include "command.hpp"
#include "commands.hpp"
#include "interrupted_runs.hpp"
#include "table_options.hpp"
#include <impactlab/io/bad_input.hpp>
#include <impactlab/io/message_text.hpp>
#include <impactlab/io/output_error.hpp>

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
      add_attractors_command(app),
      add_periodic_command(app),
      add_spectrum_command(app),
      add_continue_command(app),
      add_explore_command(app),
  };

  // GSL's default error handler aborts the process; with it off, a GSL
  // routine returns its status and the integrator turns it into an exception
  gsl_set_error_handler_off();
  // a file size limit (ulimit -f) then fails the write (EFBIG) like a full
  // disk, an OutputError with exit 4, instead of killing the process with a
  // core dump and leaving its temporaries
  std::signal(SIGXFSZ, SIG_IGN);
  // SIGINT and SIGTERM remove the outputs' temporaries before they end the program
  remove_temporaries_on_interrupt();

  const std::vector<std::string> command_line(argv, argv + argc);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& success) {
    return app.exit(success);
  } catch (const CLI::ParseError& error) {
    std::cerr << "impactlab: " << impactlab::one_line(error.what()) << '\n';
    return exit_bad_input;
  }

  const Command* parsed = nullptr;
  for (const auto& command : commands)
    if (command.app->parsed()) parsed = &command;
  try {
    if (parsed != nullptr) return parsed->run(command_line);
  } catch (const impactlab::BadInput& bad) {
    // the library names options by their names; the message spells them as flags
    std::cerr << "impactlab: " << bad_input_line(bad, parsed->job) << '\n';
    return exit_bad_input;
  } catch (const impactlab::OutputError& error) {
    std::cerr << "impactlab: output failed: " << impactlab::one_line(error.what()) << '\n';
    return exit_output_failed;
  } catch (const std::domain_error& error) {
    // a numerical library (Boost.Math's root finders and special functions)
    // refused its arguments: the run cannot go on with these values
    std::cerr << "impactlab: run stopped (numerical_failure): "
              << impactlab::one_line(error.what()) << '\n';
    return exit_stopped_early;
  } catch (const boost::math::evaluation_error& error) {
    std::cerr << "impactlab: run stopped (numerical_failure): "
              << impactlab::one_line(error.what()) << '\n';
    return exit_stopped_early;
  } catch (const std::bad_alloc&) {
    std::cerr << "impactlab: run stopped (out_of_memory): shorten the run or lower "
                 "limits.max_rows\n";
    return exit_stopped_early;
  } catch (const std::exception& error) {
    std::cerr << "impactlab: error: " << impactlab::one_line(error.what()) << '\n';
    return exit_failed;
  }
  return exit_done;
}
