// Every job's options are declared once (api/job_options.hpp): the C++
// request structs' defaults, the command line's `--help` (the built program)
// and the messages of bad input agree with the tables. The Python side is
// checked by tests/python/test_job_options.py.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/api/attractors_job.hpp>
#include <impactlab/api/basins_job.hpp>
#include <impactlab/api/continuation_job.hpp>
#include <impactlab/api/jin2003_reproduction.hpp>
#include <impactlab/api/job_options.hpp>
#include <impactlab/api/periodic_job.hpp>
#include <impactlab/api/sweep_job.hpp>
#include <impactlab/io/bad_input.hpp>

#include "support/test_support.hpp"

namespace IMPACTLAB_TEST_FILE_SCOPE {

using impactlab::FrontEnds;
using impactlab::job_option;
using impactlab::OptionSpec;
using impactlab::OptionType;

double number_default(std::string_view job, std::string_view name) {
  return std::get<double>(job_option(job, name).default_value);
}

std::string text_default(std::string_view job, std::string_view name) {
  return std::string(std::get<std::string_view>(job_option(job, name).default_value));
}

bool flag_default(std::string_view job, std::string_view name) {
  return std::get<bool>(job_option(job, name).default_value);
}

bool is_unset(std::string_view job, std::string_view name) {
  return std::holds_alternative<impactlab::Unset>(job_option(job, name).default_value);
}

TEST(JobOptions, EveryTableIsConsistent) {
  for (std::string_view job : impactlab::job_names()) {
    std::vector<std::string_view> names;
    for (const OptionSpec& spec : impactlab::job_options(job)) {
      SCOPED_TRACE(std::string(job) + " " + std::string(spec.name));
      EXPECT_EQ(std::count(names.begin(), names.end(), spec.name), 0) << "declared twice";
      names.push_back(spec.name);
      EXPECT_FALSE(spec.help.empty() && !spec.for_tests_only) << "no help";
      EXPECT_LE(spec.lower, spec.upper);
      // a required option has no default; a default lies in its range and has the type's kind
      if (spec.required) {
        EXPECT_TRUE(std::holds_alternative<impactlab::Unset>(spec.default_value));
      }
      if (const auto* number = std::get_if<double>(&spec.default_value)) {
        EXPECT_TRUE(spec.type == OptionType::number || spec.type == OptionType::integer ||
                    spec.type == OptionType::count);
        EXPECT_GE(*number, spec.lower);
        EXPECT_LE(*number, spec.upper);
        if (spec.lower_open) { EXPECT_GT(*number, spec.lower); }
      }
      if (std::holds_alternative<bool>(spec.default_value)) {
        EXPECT_EQ(spec.type, OptionType::flag);
      }
      if (std::holds_alternative<std::string_view>(spec.default_value)) {
        EXPECT_TRUE(spec.type == OptionType::text || spec.type == OptionType::file ||
                    spec.type == OptionType::text_list);
      }
      if (!spec.excludes.empty()) { EXPECT_NO_THROW(job_option(job, spec.excludes)); }
    }
  }
  EXPECT_EQ(impactlab::testing::bad_input_key([] { impactlab::job_options("no_such_job"); }),
            "job");
}

TEST(JobOptions, FlagsAndMentionsAreSpelledPerFrontEnd) {
  EXPECT_EQ(impactlab::option_flag("param2"), "--param2");
  EXPECT_EQ(impactlab::option_flag("period_tol"), "--period-tol");
  EXPECT_EQ(impactlab::option_flag("samples_per_period"), "--samples-per-period");
  const std::string reason = "must differ from " + impactlab::mention("param") + "'s key";
  EXPECT_EQ(impactlab::spell_options(reason, impactlab::option_flag),
            "must differ from --param's key");
  EXPECT_EQ(impactlab::spell_options(reason, [](std::string_view name) {
              return std::string(name);
            }),
            "must differ from param's key");
}

// The request structs of the scene API start from the tables' defaults.
TEST(JobOptions, RequestStructDefaultsAgreeWithTheTables) {
  const impactlab::SectionRequest section;
  for (std::string_view job : {"poincare", "sweep", "basins", "attractors"}) {
    SCOPED_TRACE(std::string(job));
    // no transient given: the settling transient, the library's default
    EXPECT_TRUE(is_unset(job, "transient"));
    EXPECT_TRUE(section.settle);
    EXPECT_EQ(section.max_transient_periods, number_default(job, "max_transient"));
    EXPECT_EQ(static_cast<double>(section.transient_impacts),
              number_default(job, "transient_impacts"));
    EXPECT_EQ(static_cast<double>(section.points), number_default(job, "points"));
  }
  EXPECT_EQ(section.lyapunov, flag_default("poincare", "lyapunov"));
  for (std::string_view job : {"poincare", "sweep", "basins"})
    EXPECT_EQ(section.lyapunov_spectrum, flag_default(job, "lyapunov_spectrum")) << job;

  const impactlab::SweepSpec sweep;
  EXPECT_EQ(sweep.direction, text_default("sweep", "direction"));
  EXPECT_EQ(sweep.chunks, number_default("sweep", "chunks"));
  EXPECT_FALSE(sweep.lyapunov.has_value());
  EXPECT_TRUE(is_unset("sweep", "lyapunov"));
  EXPECT_EQ(sweep.period_tolerance, number_default("sweep", "period_tol"));
  EXPECT_EQ(sweep.max_period, number_default("sweep", "max_period"));
  EXPECT_EQ(sweep.classification_tolerance, text_default("sweep", "classification_tol"));
  EXPECT_EQ(impactlab::SweepJobOptions{}.threads, number_default("sweep", "threads"));
  for (std::string_view job : {"sweep", "basins", "attractors"})
    EXPECT_EQ(impactlab::SweepJobOptions{}.batch, text_default(job, "batch")) << job;

  const impactlab::BasinsSpec basins;
  EXPECT_EQ(basins.lyapunov, flag_default("basins", "lyapunov"));
  EXPECT_EQ(basins.period_tolerance, number_default("basins", "period_tol"));
  EXPECT_EQ(basins.max_period, number_default("basins", "max_period"));
  EXPECT_EQ(basins.attractor_tolerance, number_default("basins", "attractor_tol"));
  EXPECT_FALSE(basins.entropy_box.has_value());
  EXPECT_TRUE(is_unset("basins", "entropy_box"));

  const impactlab::AttractorsSpec attractors;
  EXPECT_EQ(attractors.samples, number_default("attractors", "samples"));
  EXPECT_EQ(static_cast<double>(attractors.seed), number_default("attractors", "seed"));
  EXPECT_TRUE(attractors.box.empty());
  EXPECT_TRUE(is_unset("attractors", "box"));
  EXPECT_EQ(attractors.lyapunov, flag_default("attractors", "lyapunov"));
  EXPECT_EQ(attractors.period_tolerance, number_default("attractors", "period_tol"));
  EXPECT_EQ(attractors.max_period, number_default("attractors", "max_period"));
  EXPECT_EQ(attractors.attractor_tolerance, number_default("attractors", "attractor_tol"));
  EXPECT_EQ(attractors.match_tolerance, number_default("attractors", "match_tol"));
  EXPECT_EQ(impactlab::SweepPlan{}.match_tolerance, number_default("attractors", "match_tol"));

  const impactlab::PeriodicJob periodic;
  EXPECT_EQ(periodic.period, text_default("periodic", "period"));
  EXPECT_EQ(periodic.phase, number_default("periodic", "phase"));
  EXPECT_EQ(periodic.transient, number_default("periodic", "transient"));
  EXPECT_EQ(periodic.max_iterations, number_default("periodic", "max_iterations"));
  EXPECT_EQ(periodic.tolerance, number_default("periodic", "tolerance"));
  EXPECT_EQ(periodic.all, flag_default("periodic", "all"));
  EXPECT_EQ(periodic.starts, number_default("periodic", "starts"));
  EXPECT_TRUE(periodic.box.empty());
  EXPECT_TRUE(is_unset("periodic", "box"));
  EXPECT_EQ(static_cast<double>(periodic.seed), number_default("periodic", "seed"));
  EXPECT_EQ(impactlab::PeriodicOrbitsRequest{}.starts, number_default("periodic", "starts"));
  EXPECT_EQ(static_cast<double>(impactlab::PeriodicOrbitsRequest{}.seed),
            number_default("periodic", "seed"));

  impactlab::ContinueOptions options;
  EXPECT_TRUE(options.param2.empty() && is_unset("continue", "param2"));
  EXPECT_TRUE(options.curve.empty() && is_unset("continue", "curve"));
  EXPECT_TRUE(options.start.empty() && is_unset("continue", "start"));
  EXPECT_EQ(options.period, number_default("continue", "period"));
  EXPECT_EQ(options.section, text_default("continue", "section"));
  EXPECT_EQ(options.switch_doubling, flag_default("continue", "switch"));
  EXPECT_EQ(options.transient, number_default("continue", "transient"));
  EXPECT_EQ(options.max_points, number_default("continue", "max_points"));
  EXPECT_EQ(options.tolerance, number_default("continue", "tolerance"));
  EXPECT_EQ(options.all, flag_default("continue", "all"));
  EXPECT_EQ(options.starts, number_default("continue", "starts"));
  EXPECT_TRUE(options.box.empty() && is_unset("continue", "box"));
  EXPECT_EQ(static_cast<double>(options.seed), number_default("continue", "seed"));
  EXPECT_EQ(options.max_step, number_default("continue", "max_step"));
  // the job built from the default options carries the table's tolerance
  options.param = "omega=2:2.5";
  const impactlab::ContinuationJob job = impactlab::continuation_job(options);
  EXPECT_EQ(job.numerics.tolerance, number_default("continue", "tolerance"));
  EXPECT_EQ(job.numerics.max_points, number_default("continue", "max_points"));
  EXPECT_EQ(job.transient_periods, number_default("continue", "transient"));
  EXPECT_EQ(job.doublings, 0);
  options.switch_doubling = true;
  EXPECT_EQ(impactlab::continuation_job(options).doublings, impactlab::doublings_followed);

  std::string models;
  for (const auto& model : impactlab::Jin2003Settings{}.models)
    models += (models.empty() ? "" : ",") + model;
  EXPECT_EQ(models, text_default("reproduce", "models"));
}

// The library names options by their own names (the front ends spell them).
TEST(JobOptions, ContinuationJobNamesOptionsByTheirNames) {
  impactlab::ContinueOptions options;
  options.param = "omega=2";
  try {
    (void)impactlab::continuation_job(options);
    ADD_FAILURE() << "a malformed range was accepted";
  } catch (const impactlab::BadInput& bad) {
    EXPECT_EQ(bad.key(), "param");
  }
  options.param = "omega=2:3";
  options.curve = "fold";
  try {
    (void)impactlab::continuation_job(options);
    ADD_FAILURE() << "curve without param2 was accepted";
  } catch (const impactlab::BadInput& bad) {
    EXPECT_EQ(std::string(bad.what()), "curve = fold: needs `param2`");
  }
}

// The line of `--help` that lists `flag` (from the flag to the next option).
std::string help_entry(const std::string& help, const std::string& flag) {
  const std::string start = "\n  " + flag + " ";
  std::size_t at = help.find(start);
  if (at == std::string::npos) at = help.find("\n  " + flag + "\n");
  if (at == std::string::npos) at = help.find("\n  " + flag + "{");  // a negating flag
  if (at == std::string::npos) return {};
  const std::size_t end = help.find("\n  -", at + 1);
  return help.substr(at + 1, end == std::string::npos ? std::string::npos : end - at - 1);
}

// The command line's `--help` of every job shows each of its options with its
// help text and, where the table says so, its default.
TEST(JobOptions, CommandLineHelpAgreesWithTheTables) {
  for (std::string_view job : impactlab::job_names()) {
    const auto options = impactlab::job_options(job);
    const bool on_command_line = std::any_of(options.begin(), options.end(), [](const auto& spec) {
      return spec.front_ends != FrontEnds::python;
    });
    if (!on_command_line) continue;  // Python's bench of one scene
    const auto run = impactlab::testing::run_impactlab({std::string(job), "--help"});
    ASSERT_EQ(run.status, 0) << job << run.err;
    const std::string help = "\n" + run.out;
    for (const OptionSpec& spec : options) {
      SCOPED_TRACE(std::string(job) + " " + std::string(spec.name));
      const std::string flag = spec.positional ? std::string(spec.name)
                                               : impactlab::option_flag(spec.name);
      const std::string entry = help_entry(help, flag);
      if (spec.for_tests_only || spec.front_ends == FrontEnds::python) {
        EXPECT_TRUE(entry.empty()) << "listed: " << entry;
        continue;
      }
      ASSERT_FALSE(entry.empty()) << "not listed in:\n" << run.out;
      EXPECT_NE(entry.find(impactlab::spell_options(spec.help, impactlab::option_flag)),
                std::string::npos)
          << entry;
      if (spec.required) { EXPECT_NE(entry.find("REQUIRED"), std::string::npos) << entry; }
      // the default CLI11 shows: FLAG TYPE[:CHECK]=DEFAULT, before the help
      // text (which follows two spaces or a line break)
      const std::string line = entry.substr(2, entry.find('\n') - 2);
      const std::string head = line.substr(0, line.find("  "));
      const std::size_t equals = head.find('=');
      const bool shown_default = spec.default_in_help && spec.type != OptionType::flag &&
                                 !std::holds_alternative<impactlab::Unset>(spec.default_value);
      if (!shown_default) {
        EXPECT_EQ(equals, std::string::npos) << head;
        continue;
      }
      ASSERT_NE(equals, std::string::npos) << head;
      std::string shown = head.substr(equals + 1);
      shown = shown.substr(0, shown.find(' '));
      if (const auto* number = std::get_if<double>(&spec.default_value)) {
        EXPECT_EQ(std::stod(shown), *number) << head;
      } else if (const auto* text = std::get_if<std::string_view>(&spec.default_value)) {
        // a list is shown in brackets
        if (spec.type == OptionType::text_list) shown = shown.substr(1, shown.size() - 2);
        EXPECT_EQ(shown, *text) << head;
      }
    }
  }
}

}  // namespace
