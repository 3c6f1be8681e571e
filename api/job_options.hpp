// Each job's options, declared once: name, type, default, range, unit and
// help. The CLI makes its flags, `--help`, shown defaults and range checks
// from these tables; the Python package its keyword defaults, validation and
// docstrings; the tests check that both, and the C++ request structs, agree
// with them.
//
// An option is named by its own name (`param2`, `period_tol`). Only the CLI
// spells it as a flag: `--` + the name with `_` turned into `-`
// (`--param2`, `--period-tol`). A help text or a BadInput reason that names
// another option writes it between backquotes (`param`), and each front end
// spells it its own way (spell_options).
#pragma once

#include <functional>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace impactlab {

enum class OptionType {
  number,       // a finite double within [lower, upper]
  integer,      // a whole number (int) within [lower, upper]
  count,        // a whole number written in digits only (std::uint64_t) within [lower, upper]
  text,         // a word or a path; `choices` lists the accepted words where they are fixed
  file,         // the path of an existing file
  flag,         // present or absent
  text_list,    // several texts: repeated, or comma-separated where `comma_separated`
  number_list,  // several finite numbers, comma-separated
};

// Which front ends offer the option: the CLI alone holds output directories,
// plots and resumption; Python alone the keywords of its own bench.
enum class FrontEnds { both, cli, python };

// No default: the option is unset unless given (Python's None).
struct Unset {
  bool operator==(const Unset&) const = default;
};
// A default: a flag's state, a number (number, integer, count), a text (text,
// file; a text_list's items comma-separated) or a number_list's numbers.
using OptionDefault = std::variant<Unset, bool, double, std::string_view, std::vector<double>>;

struct OptionSpec {
  std::string_view name;
  OptionType type = OptionType::text;
  std::string_view help;  // other options named as `name`
  OptionDefault default_value = Unset{};
  // whether `--help` states the default; false where the help text says it
  // or the default means "not used" (0 impacts: the transient counts periods)
  bool default_in_help = true;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
  bool lower_open = false;  // (lower, upper]: a positive number has lower 0, open
  std::string_view unit = "";
  std::vector<std::string_view> choices = {};  // text: the accepted words, where fixed
  FrontEnds front_ends = FrontEnds::both;
  bool positional = false;       // the CLI takes it without a flag (the scene, the paper)
  bool required = false;         // no default: it must be given
  bool for_tests_only = false;   // left out of `--help` and the Python signatures
  int max_count = 0;             // lists: at most this many (0: any number)
  bool comma_separated = false;  // lists: one argument, items separated by commas
  std::string_view excludes = "";  // an option that cannot be given with this one
};

// The options of `job` in the order the CLI lists them: simulate, poincare,
// sweep, basins, attractors, periodic, continue, compare, bench (the CLI's study),
// work_precision (Python's bench of one scene), reproduce, spectrum, explore.
// BadInput (key `job`) for another name.
std::span<const OptionSpec> job_options(std::string_view job);

// The names job_options knows, in that order.
std::span<const std::string_view> job_names();

// The option `name` of `job`; std::out_of_range where it has none.
const OptionSpec& job_option(std::string_view job, std::string_view name);

// The command line's spelling of an option: `--` + name, `_` turned into `-`.
std::string option_flag(std::string_view name);

// `text` with every option named between backquotes spelled by `spell`
// (`param` becomes `--param` on the command line, `param` in Python).
std::string spell_options(std::string_view text,
                          const std::function<std::string(std::string_view)>& spell);

// The backquoted mention of an option in a BadInput reason or a help text.
std::string mention(std::string_view name);

}  // namespace impactlab
