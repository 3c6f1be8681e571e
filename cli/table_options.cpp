#include "table_options.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <impactlab/io/message_text.hpp>
#include "command.hpp"

namespace impactlab::cli {

namespace {

// CLI11 puts the validator's text after the option's name; the value is
// shortened so that the message stays one short line
std::string shown(const std::string& text) { return elide_value(text); }

std::string check_number(const std::string& text, bool positive) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0') return "not a number: " + shown(text);
  if (!std::isfinite(value)) return "not a finite number: " + shown(text);
  if (positive && !(value > 0.0)) return "must be > 0: " + shown(text);
  return {};
}

std::string check_number_in(const std::string& text, double lower, double upper) {
  if (auto error = check_number(text, false); !error.empty()) return error;
  const double value = std::strtod(text.c_str(), nullptr);
  if (value < lower || value > upper)
    return fmt::format("{} is outside [{}, {}]", shown(text), lower, upper);
  return {};
}

std::string check_count_in(const std::string& text, std::uint64_t lower, std::uint64_t upper) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size())
    return "not a whole number >= 0: " + shown(text);
  if (value < lower || value > upper)
    return fmt::format("{} is outside [{}, {}]", shown(text), lower, upper);
  return {};
}

// A finite number; a positive finite number. CLI11's own range checks let inf
// through and print the whole double range.
const CLI::Validator& finite_number() {
  static const CLI::Validator validator(
      [](std::string& text) { return check_number(text, false); }, "FINITE");
  return validator;
}

const CLI::Validator& positive_number() {
  static const CLI::Validator validator(
      [](std::string& text) { return check_number(text, true); }, "POSITIVE");
  return validator;
}

CLI::Validator number_in(double lower, double upper) {
  return CLI::Validator(
      [lower, upper](std::string& text) { return check_number_in(text, lower, upper); },
      fmt::format("FINITE in [{}, {}]", lower, upper));
}

CLI::Validator count_in(std::uint64_t lower, std::uint64_t upper) {
  return CLI::Validator(
      [lower, upper](std::string& text) { return check_count_in(text, lower, upper); },
      fmt::format("WHOLE in [{}, {}]", lower, upper));
}

double number_default(const OptionSpec& spec) {
  if (const auto* number = std::get_if<double>(&spec.default_value)) return *number;
  return 0.0;
}

std::string text_default(const OptionSpec& spec) {
  if (const auto* text = std::get_if<std::string_view>(&spec.default_value))
    return std::string(*text);
  return {};
}

bool has_default(const OptionSpec& spec) {
  return !std::holds_alternative<Unset>(spec.default_value);
}

// the check of a number's range: finite, positive, non-negative, or within
// [lower, upper]
CLI::Validator number_check(const OptionSpec& spec) {
  const bool below_unbounded = std::isinf(spec.lower), above_unbounded = std::isinf(spec.upper);
  if (below_unbounded && above_unbounded) return finite_number();
  if (spec.lower == 0.0 && above_unbounded && spec.lower_open) return positive_number();
  if (spec.lower == 0.0 && above_unbounded) return CLI::NonNegativeNumber;
  return number_in(spec.lower, spec.upper);
}

template <class Whole>
CLI::Validator whole_check(const OptionSpec& spec) {
  return CLI::Range(static_cast<Whole>(spec.lower), static_cast<Whole>(spec.upper));
}

}  // namespace

std::string flag_spelling(std::string_view name) { return option_flag(name); }

CLI::App* add_subcommand(CLI::App& program, const std::string& name, const std::string& help) {
  return program.add_subcommand(name, help);
}

bool option_given(const CLI::Option* option) { return option != nullptr && option->count() > 0; }

void add_positional(CLI::App& command, const std::string& name, std::string& value,
                    const std::string& help) {
  command.add_option(name, value, help);
}

TableOptions::TableOptions(CLI::App& command, std::string_view job)
    : command_(command), job_(job) {}

std::string TableOptions::cli_name(const OptionSpec& spec) const {
  return spec.positional ? std::string(spec.name) : option_flag(spec.name);
}

std::string TableOptions::help(const OptionSpec& spec) const {
  return spell_options(spec.help, flag_spelling);
}

CLI::Option* TableOptions::finish(CLI::Option* option, const OptionSpec& spec) {
  if (spec.required) option->required();
  if (spec.max_count > 0) {
    // counted after parsing, so that one too many is refused naming the
    // option, as every other bad input is (CLI11's own count check says
    // "At Most 2 required but received 3"); one check per command, for all
    // its counted options
    if (counted_->empty())
      command_.parse_complete_callback([counted = counted_] {
        for (const CountLimit& limit : *counted)
          if (limit.option->count() > static_cast<std::size_t>(limit.most))
            throw CLI::ValidationError(
                limit.flag + " = " + limit.option->as<std::vector<std::string>>().back(),
                fmt::format("given {} times; at most {}", limit.option->count(), limit.most));
      });
    counted_->push_back({option, cli_name(spec), spec.max_count});
  }
  if (spec.comma_separated) option->delimiter(',');
  if (spec.for_tests_only) option->group("");
  if (spec.default_in_help && has_default(spec) && spec.type != OptionType::flag)
    option->capture_default_str();
  if (!spec.excludes.empty()) option->excludes(added_.at(spec.excludes));
  added_[spec.name] = option;
  return option;
}

CLI::Option* TableOptions::add(std::string_view name, double& value) {
  const OptionSpec& spec = job_option(job_, name);
  value = number_default(spec);
  return finish(command_.add_option(cli_name(spec), value, help(spec))->check(number_check(spec)),
                spec);
}

CLI::Option* TableOptions::add(std::string_view name, int& value) {
  const OptionSpec& spec = job_option(job_, name);
  value = static_cast<int>(number_default(spec));
  return finish(
      command_.add_option(cli_name(spec), value, help(spec))->check(whole_check<int>(spec)),
      spec);
}

CLI::Option* TableOptions::add(std::string_view name, long& value) {
  const OptionSpec& spec = job_option(job_, name);
  value = static_cast<long>(number_default(spec));
  return finish(
      command_.add_option(cli_name(spec), value, help(spec))->check(whole_check<long>(spec)),
      spec);
}

CLI::Option* TableOptions::add(std::string_view name, std::uint64_t& value) {
  const OptionSpec& spec = job_option(job_, name);
  value = static_cast<std::uint64_t>(number_default(spec));
  return finish(command_.add_option(cli_name(spec), value, help(spec))
                    ->check(count_in(static_cast<std::uint64_t>(spec.lower),
                                     static_cast<std::uint64_t>(spec.upper))),
                spec);
}

CLI::Option* TableOptions::add(std::string_view name, std::string& value) {
  const OptionSpec& spec = job_option(job_, name);
  value = text_default(spec);
  CLI::Option* option = command_.add_option(cli_name(spec), value, help(spec));
  if (spec.type == OptionType::file) option->check(CLI::ExistingFile);
  return finish(option, spec);
}

CLI::Option* TableOptions::add(std::string_view name, std::vector<std::string>& value) {
  const OptionSpec& spec = job_option(job_, name);
  value.clear();
  const std::string items = text_default(spec);
  for (std::size_t from = 0; from < items.size();) {
    const std::size_t comma = std::min(items.find(',', from), items.size());
    value.push_back(items.substr(from, comma - from));
    from = comma + 1;
  }
  return finish(command_.add_option(cli_name(spec), value, help(spec)), spec);
}

CLI::Option* TableOptions::add(std::string_view name, std::vector<double>& value) {
  const OptionSpec& spec = job_option(job_, name);
  if (const auto* numbers = std::get_if<std::vector<double>>(&spec.default_value))
    value = *numbers;
  else
    value.clear();
  return finish(command_.add_option(cli_name(spec), value, help(spec)), spec);
}

CLI::Option* TableOptions::add(std::string_view name, bool& value) {
  const OptionSpec& spec = job_option(job_, name);
  if (const auto* state = std::get_if<bool>(&spec.default_value))
    value = *state;
  else
    value = false;
  return finish(command_.add_flag(cli_name(spec), value, help(spec)), spec);
}

CLI::Option* TableOptions::add_negation(std::string_view name, bool& value) {
  const OptionSpec& spec = job_option(job_, name);
  value = true;
  return finish(command_.add_flag("!" + cli_name(spec), value, help(spec)), spec);
}

std::string bad_input_line(const BadInput& bad, std::string_view job) {
  const std::string what = bad.what();
  const std::string prefix = elide_value(bad.key()) + " = " + elide_value(bad.value()) + ": ";
  if (job.empty() || !what.starts_with(prefix)) return one_line(what);
  // the key, each part of a pair such as x/y, as the command line spells it
  const auto options = job_options(job);
  const auto spelled = [&](std::string_view part) {
    const auto spec = std::find_if(options.begin(), options.end(), [&](const OptionSpec& row) {
      return row.name == part && !row.positional;
    });
    return spec == options.end() ? std::string(part) : option_flag(part);
  };
  std::string key;
  std::string_view rest = bad.key();
  for (std::size_t slash = rest.find('/');; slash = rest.find('/')) {
    key += spelled(rest.substr(0, slash));
    if (slash == std::string_view::npos) break;
    key += '/';
    rest.remove_prefix(slash + 1);
  }
  return one_line(elide_value(key) + " = " + elide_value(bad.value()) + ": " +
                  spell_options(std::string_view(what).substr(prefix.size()), flag_spelling));
}

}  // namespace impactlab::cli
