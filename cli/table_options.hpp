// A job's options (api/job_options.hpp) as the command line's: each row
// becomes its flag (`--` + the name, `_` as `-`), or a positional argument,
// with its help text, its default (set, and shown where the row says so), its
// range check and its exclusions. A command binds each row to the variable
// that receives the value; the variable's type gives the type CLI11 shows.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <impactlab/api/job_options.hpp>
#include <impactlab/io/bad_input.hpp>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace impactlab::cli {

// A subcommand `name` of the program, with its one-line help.
CLI::App* add_subcommand(CLI::App& program, const std::string& name, const std::string& help);
// Whether the option was given on the command line (false for none).
bool option_given(const CLI::Option* option);
// An optional positional argument of a command that runs no job.
void add_positional(CLI::App& command, const std::string& name, std::string& value,
                    const std::string& help);

class TableOptions {
 public:
  TableOptions(CLI::App& command, std::string_view job);

  CLI::Option* add(std::string_view name, double& value);
  CLI::Option* add(std::string_view name, int& value);
  CLI::Option* add(std::string_view name, long& value);
  CLI::Option* add(std::string_view name, std::uint64_t& value);
  CLI::Option* add(std::string_view name, std::string& value);
  CLI::Option* add(std::string_view name, std::vector<std::string>& value);
  CLI::Option* add(std::string_view name, std::vector<double>& value);
  CLI::Option* add(std::string_view name, bool& value);  // a flag
  // a flag `no_X` that turns `value` (true unless given) off
  CLI::Option* add_negation(std::string_view name, bool& value);

 private:
  // the option or positional argument with its help, as CLI11 names it
  [[nodiscard]] std::string cli_name(const OptionSpec& spec) const;
  [[nodiscard]] std::string help(const OptionSpec& spec) const;
  // required, hidden, list sizes, the shown default and exclusions
  CLI::Option* finish(CLI::Option* option, const OptionSpec& spec);

  // an option given at most `most` times, counted once the command is parsed
  struct CountLimit {
    CLI::Option* option;
    std::string flag;
    int most;
  };

  CLI::App& command_;
  std::string_view job_;
  std::map<std::string_view, CLI::Option*> added_;
  // shared with the command's one parse-complete check
  std::shared_ptr<std::vector<CountLimit>> counted_ = std::make_shared<std::vector<CountLimit>>();
};

// The command line's spelling of an option named in help or a message.
std::string flag_spelling(std::string_view name);

// One line for bad input to `job`'s command: the BadInput message with the
// key spelled as the command line spells it where it names one of the job's
// options (`param2` -> `--param2`; "x/y" -> "--x/--y"; a scene key as it is),
// and every option named in the reason as a flag.
std::string bad_input_line(const BadInput& bad, std::string_view job);

}  // namespace impactlab::cli
