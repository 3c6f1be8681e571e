#include <impactlab/api/job_options.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>

#include <impactlab/analysis/continuation.hpp>
#include <impactlab/analysis/section.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

using std::string_view;
using Options = std::vector<OptionSpec>;

// tables made of shared parts and a job's own options, in the CLI's order
Options joined(std::initializer_list<Options> parts) {
  Options all;
  for (const Options& part : parts) all.insert(all.end(), part.begin(), part.end());
  return all;
}

// --- the shared parts ------------------------------------------------------

OptionSpec scene_argument(string_view help) {
  return {.name = "scene", .type = OptionType::text, .help = help,
          .default_value = string_view("jin2003"), .front_ends = FrontEnds::cli,
          .positional = true};
}

OptionSpec scene_settings(string_view help) {
  return {.name = "set", .type = OptionType::text_list, .help = help,
          .front_ends = FrontEnds::cli};
}

OptionSpec output_directory(string_view help = "output directory (default out/<scene>)") {
  return {.name = "out", .type = OptionType::text, .help = help, .front_ends = FrontEnds::cli};
}

OptionSpec quiet() {
  return {.name = "quiet", .type = OptionType::flag, .help = "print nothing but errors",
          .default_value = false, .front_ends = FrontEnds::cli};
}

// the scene, its settings and the time span of a run (simulate, compare)
Options run_options() {
  return {
      scene_argument("built-in scene name or path to a scene file (.toml)"),
      scene_settings("KEY=VALUE, repeatable: a parameter (omega, V0, e_n, ...) or a dotted key "
                     "(initial.theta, integrator.rtol)"),
      {.name = "t_end", .type = OptionType::number,
       .help = "end time (s), after t0; excludes `periods`", .unit = "s"},
      {.name = "periods", .type = OptionType::number,
       .help = "forcing periods to run from t0 (default 100)", .lower = 0.0, .lower_open = true,
       .unit = "forcing periods", .excludes = "t_end"},
      output_directory(),
      {.name = "threads", .type = OptionType::integer,
       .help = "worker threads (a single run uses one)", .default_value = 1.0,
       .default_in_help = false, .lower = 1, .upper = 1024, .front_ends = FrontEnds::cli},
      quiet(),
  };
}

// the scene, the section, the transient and the points recorded (poincare,
// sweep, basins); `points_help` says what the points count for the job
Options section_options(string_view points_help) {
  return {
      scene_argument("built-in scene name or path to a scene file (.toml)"),
      scene_settings("KEY=VALUE, repeatable: a parameter (omega, V0, e_n, ...) or a dotted key"),
      output_directory(),
      quiet(),
      {.name = "section", .type = OptionType::text,
       .help = "strobe[:PHASE] (forcing phase wt mod 2pi, rad), impact[:WALL] (+1, -1, 0 = any "
               "wall), or a user-given section q=LEVEL[:up|down|both] or "
               "qdot=LEVEL[:up|down|both]",
       .default_value = string_view("strobe")},
      {.name = "transient_impacts", .type = OptionType::count,
       .help = "discard this many impacts instead of periods", .default_value = 0.0,
       .default_in_help = false, .lower = 0, .upper = 1e9, .unit = "impacts"},
      {.name = "transient", .type = OptionType::number,
       .help = "forcing periods discarded first, exactly (default: at least 100, then until the "
               "stroboscopic points settle, at most `max_transient`)",
       .lower = 0, .upper = 1e9, .unit = "forcing periods", .excludes = "transient_impacts"},
      {.name = "max_transient", .type = OptionType::number,
       .help = "most forcing periods the settling transient runs; a point still converging then "
               "is marked not_settled",
       .default_value = SectionRequest{}.max_transient_periods, .lower = 0, .upper = 1e9,
       .unit = "forcing periods", .excludes = "transient"},
      {.name = "points", .type = OptionType::count, .help = points_help, .default_value = 50.0,
       .lower = 1, .upper = 1e8},
      {.name = "plot", .type = OptionType::flag,
       .help = "also write a PNG (matplotlib through $IMPACTLAB_PYTHON, else /usr/bin/python3)", .default_value = false,
       .front_ends = FrontEnds::cli},
  };
}

// all N Lyapunov exponents (poincare, sweep, basins)
OptionSpec lyapunov_spectrum(string_view help) {
  return {.name = "lyapunov_spectrum", .type = OptionType::flag, .help = help,
          .default_value = false};
}

// how a sweep tells periods apart (sweep, basins)
Options period_detection() {
  return {
      {.name = "period_tol", .type = OptionType::number,
       .help = "relative distance under which section points count as repeating",
       .default_value = 1e-6, .lower = 0.0, .lower_open = true},
      {.name = "max_period", .type = OptionType::integer, .help = "longest period looked for",
       .default_value = 16.0, .lower = 1, .upper = 10000, .unit = "section points"},
  };
}

OptionSpec sweep_threads() {
  return {.name = "threads", .type = OptionType::integer, .help = "worker threads",
          .default_value = 1.0, .lower = 1, .upper = 1024};
}

OptionSpec batch() {
  return {.name = "batch", .type = OptionType::text,
          .help = "on: where the stepper is taylor, each thread runs its trajectories in the lanes "
                  "of a batch whose Taylor series are computed together; off: one at a time. The "
                  "files are the same",
          .default_value = string_view("on"), .choices = {"on", "off"}};
}

OptionSpec resume(string_view help) {
  return {.name = "resume", .type = OptionType::flag, .help = help, .default_value = false,
          .front_ends = FrontEnds::cli};
}

// for tests of resume: stop (exit 3, checkpoint kept) after this many new points per rank
OptionSpec stop_after() {
  return {.name = "stop_after", .type = OptionType::integer, .lower = 1,
          .upper = 1099511627776.0, .unit = "points", .front_ends = FrontEnds::cli,
          .for_tests_only = true};
}

// --- the jobs ----------------------------------------------------------------

Options simulate_options() {
  return joined({run_options(),
                 {{.name = "sample", .type = OptionType::number,
                   .help = "also write trajectory.csv sampled every DT s", .lower = 0.0,
                   .lower_open = true, .unit = "s"},
                  {.name = "plot", .type = OptionType::flag,
                   .help = "also draw simulation.png (the coordinate against time with the "
                           "walls, impacts and contact phases, and the phase portrait); without "
                           "`sample`, 64 samples per forcing period, at most 20000",
                   .default_value = false, .front_ends = FrontEnds::cli}}});
}

Options poincare_options() {
  return joined(
      {section_options("section points recorded (strobe: forcing periods; impact: impacts)"),
       {{.name = "lyapunov", .type = OptionType::flag,
         .help = "also the largest Lyapunov exponent over the recorded periods (meta.json)",
         .default_value = false},
        lyapunov_spectrum("also all N Lyapunov exponents over the recorded periods (meta.json) "
                          "and their running estimate (lyapunov.csv)")}});
}

Options sweep_options() {
  return joined(
      {section_options("section points recorded per value (strobe: forcing periods; impact: "
                       "impacts)"),
       {{.name = "param", .type = OptionType::text_list,
         .help = "NAME=FROM:TO:N, once (1D bifurcation sweep) or twice (2D map)",
         .required = true, .max_count = 2},
        {.name = "direction", .type = OptionType::text,
         .help = "1D: follow the attractor up, down or both ways",
         .default_value = string_view("up"), .choices = {"up", "down", "both"}},
        sweep_threads(),
        batch(),
        {.name = "chunks", .type = OptionType::integer,
         .help = "1D: split each direction into this many continuation runs, each from the "
                 "scene's initial state (lets threads share a 1D sweep)",
         .default_value = 1.0, .lower = 1, .upper = 1000000},
        {.name = "lyapunov", .type = OptionType::flag,
         .help = "compute the largest Lyapunov exponent (default: on for 2D, off for 1D)"},
        {.name = "no_lyapunov", .type = OptionType::flag, .help = "do not compute it in a 2D map",
         .default_value = false, .front_ends = FrontEnds::cli, .excludes = "lyapunov"},
        lyapunov_spectrum("also all N Lyapunov exponents of each point (columns lyapunov1..N)")},
       period_detection(),
       {{.name = "classification_tol", .type = OptionType::text,
         .help = "auto: a 2D map (classes only) integrates at the scene's "
                 "integrator.classification_* unless an integrator key is `set`; off: at the "
                 "scene's integrator (the Lyapunov exponent always is)",
         .default_value = string_view("auto"), .choices = {"auto", "off"}},
        resume("reuse the finished points of an interrupted run of the same sweep in `out`"),
        stop_after()}});
}

Options basins_options() {
  return joined(
      {section_options("section points recorded per initial condition (strobe: forcing "
                       "periods; impact: impacts)"),
       {{.name = "x", .type = OptionType::text,
         .help = "KEY=FROM:TO:N: the first grid key (fastest)", .required = true},
        {.name = "y", .type = OptionType::text, .help = "KEY=FROM:TO:N: the second grid key",
         .required = true},
        sweep_threads(),
        batch(),
        {.name = "lyapunov", .type = OptionType::flag,
         .help = "also compute the largest Lyapunov exponent", .default_value = false},
        lyapunov_spectrum(
            "also all N Lyapunov exponents of each initial condition (columns lyapunov1..N)")},
       period_detection(),
       {{.name = "attractor_tol", .type = OptionType::number,
         .help = "relative distance under which two canonical section points are one attractor",
         .default_value = 1e-4, .lower = 0.0, .lower_open = true},
        {.name = "entropy_box", .type = OptionType::integer,
         .help = "box side for the basin entropies, at most the grid's shorter side (default 5, "
                 "or the shorter side where that is smaller)",
         .lower = 1, .upper = 100000, .unit = "grid points"},
        resume("reuse the finished points of an interrupted run of the same map in `out`"),
        stop_after()}});
}

Options attractors_options() {
  return joined(
      {section_options("section points recorded per sample (strobe: forcing periods; impact: "
                       "impacts)"),
       {{.name = "param", .type = OptionType::text,
         .help = "NAME=FROM:TO:N: the parameter the attractors are followed along",
         .required = true},
        {.name = "samples", .type = OptionType::integer,
         .help = "initial states sampled from the box at each value",
         .default_value = 100.0, .lower = 1, .upper = 10000000, .unit = "samples"},
        {.name = "box", .type = OptionType::text_list,
         .help = "KEY=FROM:TO, repeatable: an initial-state key and the range its samples are "
                 "drawn from, uniformly (default: every initial.* key the model reads, within 1 "
                 "of the scene's value, narrowed until the oscillator accepts every corner)"},
        {.name = "seed", .type = OptionType::count,
         .help = "seed of the samples: the same seed draws the same initial states whatever "
                 "the threads",
         .default_value = 1.0, .lower = 0, .upper = 1.8e19},
        sweep_threads(),
        batch(),
        {.name = "lyapunov", .type = OptionType::flag,
         .help = "also each attractor's largest Lyapunov exponent (the mean over its samples)",
         .default_value = false}},
       period_detection(),
       {{.name = "attractor_tol", .type = OptionType::number,
         .help = "relative distance under which two canonical section points are one attractor",
         .default_value = 1e-4, .lower = 0.0, .lower_open = true},
        {.name = "match_tol", .type = OptionType::number,
         .help = "relative distance (Hausdorff, over 1 + the largest |(q, qdot)|) under which "
                 "attractors at neighbouring values are one attractor followed",
         .default_value = 0.05, .lower = 0.0, .lower_open = true},
        resume("reuse the finished samples of an interrupted run of the same job in `out`"),
        stop_after()}});
}

// every periodic orbit of a period, by deflated Newton shooting from starts
// drawn from a box of initial states (periodic, continue): `all_help` says
// what the job does with them
Options every_orbit_options(string_view all_help) {
  return {
      {.name = "all", .type = OptionType::flag, .help = all_help, .default_value = false},
      {.name = "starts", .type = OptionType::integer,
       .help = "with `all`: initial states drawn from the box, one Newton run each",
       .default_value = 20.0, .lower = 1, .upper = 1000000, .unit = "starts"},
      {.name = "box", .type = OptionType::text_list,
       .help = "with `all`: KEY=FROM:TO, repeatable: an initial-state key and the range its "
               "starts are drawn from, uniformly (default: every initial.* key the model reads, "
               "within 1 of the scene's value, narrowed until the oscillator accepts every "
               "corner)"},
      {.name = "seed", .type = OptionType::count,
       .help = "with `all`: seed of the starts: the same seed draws the same states",
       .default_value = 1.0, .lower = 0, .upper = 1.8e19},
  };
}

Options periodic_options() {
  constexpr double two_pi = 6.283185307179586;  // rad: the largest section phase
  return joined({{
      scene_argument("built-in scene name or path"),
      scene_settings("KEY=VALUE, repeatable"),
      output_directory(),
      quiet(),
      {.name = "period", .type = OptionType::text,
       .help = "n: the orbit's period in forcing periods, or auto (the period of the "
               "stroboscopic points after the transient)",
       .default_value = string_view("auto"), .unit = "forcing periods"},
      {.name = "phase", .type = OptionType::number, .help = "section phase omega t mod 2 pi (rad)",
       .default_value = 0.0, .lower = 0.0, .upper = two_pi, .unit = "rad"},
      {.name = "transient", .type = OptionType::number, .help = "forcing periods run first",
       .default_value = 100.0, .lower = 0, .upper = 1e9, .unit = "forcing periods"},
      {.name = "max_iterations", .type = OptionType::integer, .help = "Newton iterations",
       .default_value = 30.0, .lower = 1, .upper = 1000},
      {.name = "tolerance", .type = OptionType::number, .help = "relative residual",
       .default_value = 1e-11, .lower = 0.0, .lower_open = true}},
      every_orbit_options(
          "every orbit of the period: Newton shooting from `starts` states drawn from `box`, "
          "each deflated by the orbits found before; writes orbits.csv (`period` auto means "
          "1; `transient` is not used)")});
}

Options continue_options() {
  return joined({{
      scene_argument("built-in scene name or path"),
      scene_settings("KEY=VALUE, repeatable"),
      output_directory(),
      quiet(),
      {.name = "param", .type = OptionType::text, .help = "NAME=FROM:TO: the scene key continued",
       .required = true},
      {.name = "param2", .type = OptionType::text,
       .help = "NAME=FROM:TO: follow the first located fold, period doubling or grazing point of "
               "the branch (run at NAME=FROM) in (`param`, NAME) to NAME=TO (with `switch`: of "
               "each doubled branch too); writes curve.csv"},
      {.name = "curve", .type = OptionType::text,
       .help = "fold|period_doubling|grazing|contact_onset|contact_end|contact_boundary|"
               "neimark_sacker|chatter_onset: the bifurcation or boundary (the pendulum's V0*omega = g) whose "
               "curve `param2` follows (default: the first located fold, period doubling or grazing); a type "
               "the branch has no located point of is refused",
       .choices = {"fold", "period_doubling", "grazing", "contact_onset", "contact_end",
                   "contact_boundary", "neimark_sacker", "chatter_onset"}},
      {.name = "period", .type = OptionType::integer,
       .help = "n: the orbit's period in forcing periods", .default_value = 1.0, .lower = 1,
       .upper = 1000, .unit = "forcing periods"},
      {.name = "section", .type = OptionType::text,
       .help = "strobe[:PHASE], or impact:WALL (+1 or -1): the impact map, state (the impact's "
               "forcing phase, the rate before it)",
       .default_value = string_view("strobe")},
      {.name = "switch", .type = OptionType::flag,
       .help = "at a period doubling, continue the doubled orbit (the cascade, up to 3 "
               "doublings); with `param2`, also follow the curve through each codimension-two "
               "point of the curve",
       .default_value = false},
      {.name = "start", .type = OptionType::number_list,
       .help = "Q,QDOT (a model file: its N states): the start on the section (else the "
               "transient's end); impact section: PHASE,QDOT",
       .comma_separated = true},
      {.name = "transient", .type = OptionType::number, .help = "forcing periods run for the start",
       .default_value = ContinuationJob{}.transient_periods, .lower = 0, .upper = 1e9,
       .unit = "forcing periods"},
      {.name = "max_points", .type = OptionType::integer, .help = "points per branch",
       .default_value = static_cast<double>(ContinuationRequest{}.max_points), .lower = 2,
       .upper = 1000000},
      {.name = "tolerance", .type = OptionType::number,
       .help = "Newton residual |P^n(x) - x| / (1 + |x|)",
       .default_value = ContinuationRequest{}.tolerance, .lower = 0.0, .lower_open = true},
      {.name = "max_step", .type = OptionType::number,
       .help = "largest arclength step in (q, qdot, parameter) (default: 1/50 of the range)",
       .default_value = ContinuationRequest{}.max_step, .lower = 0.0},
      {.name = "no_normal_forms", .type = OptionType::flag,
       .help = "skip the discontinuity map and normal form at each located grazing point "
               "(grazing.json), and the kick signs watched along a grazing curve "
               "(docs/analysis.md)",
       .default_value = false},
      {.name = "plot", .type = OptionType::flag,
       .help = "draw continuation.png (scripts/plot_continuation.py): stable solid, unstable "
               "dashed, without multipliers (an impulse on the friction cone's edge) dotted, "
               "bifurcations marked; with a located grazing point grazing.png "
               "(scripts/plot_grazing.py): its predicted scenario beside the sweep's impacts",
       .default_value = false, .front_ends = FrontEnds::cli},
      {.name = "with_sweep", .type = OptionType::text,
       .help = "a brute-force sweep's bifurcation.csv of the same parameter, drawn under the "
               "branch; with `param2` a 2D sweep's classes.csv under the curve (implies `plot`)",
       .front_ends = FrontEnds::cli}},
      every_orbit_options(
          "continue every orbit of the period that periodic `all` finds at FROM (from "
          "`starts` states drawn from `box`): branches not connected to the scene's attractor "
          "appear too (stroboscopic section, no `param2`)")});
}

Options compare_options() {
  return joined({run_options(),
                 {{.name = "models", .type = OptionType::text,
                   .help = "comma-separated models (newton,paper,rigid); NAME[:KEY=VALUE]... "
                           "gives a model scene settings of its own; default: every model the "
                           "scene accepts",
                   .default_value = string_view(""), .default_in_help = false}}});
}

Options bench_options() {
  return {
      {.name = "out", .type = OptionType::text, .help = "output directory",
       .default_value = string_view("notebooks_data/bench"), .front_ends = FrontEnds::cli},
      {.name = "quick", .type = OptionType::flag, .help = "a short study (seconds), for tests",
       .default_value = false, .front_ends = FrontEnds::cli},
      {.name = "no_scipy", .type = OptionType::flag, .help = "skip the SciPy event loop",
       .default_value = false, .front_ends = FrontEnds::cli},
      {.name = "no_plots", .type = OptionType::flag, .help = "skip the plots",
       .default_value = false, .front_ends = FrontEnds::cli},
      {.name = "repetitions", .type = OptionType::integer,
       .help = "timed repetitions per point (median; default 3, 1 with `quick`)", .lower = 1,
       .upper = 100, .front_ends = FrontEnds::cli},
      {.name = "python", .type = OptionType::file,
       .help = "Python with NumPy, SciPy and matplotlib",
       .default_value = string_view("/usr/bin/python3"), .front_ends = FrontEnds::cli},
      quiet(),
  };
}

Options work_precision_options() {
  return {
      {.name = "methods", .type = OptionType::text_list,
       .help = "stepper names (default: every stepper of the scene)",
       .front_ends = FrontEnds::python},
      {.name = "rtols", .type = OptionType::number_list,
       .help = "relative tolerances; atol = atol_ratio rtol",
       .default_value = std::vector<double>{1e-6, 1e-8, 1e-10}, .lower = 0.0, .upper = 1.0,
       .lower_open = true, .front_ends = FrontEnds::python},
      {.name = "atol_ratio", .type = OptionType::number, .help = "atol over rtol",
       .default_value = 1e-2, .lower = 0.0, .lower_open = true, .front_ends = FrontEnds::python},
      {.name = "periods", .type = OptionType::number, .help = "forcing periods of each timed run",
       .default_value = 50.0, .lower = 0.0, .lower_open = true, .unit = "forcing periods",
       .front_ends = FrontEnds::python},
      {.name = "reference_periods", .type = OptionType::number,
       .help = "forcing periods the errors are measured over", .default_value = 20.0,
       .lower = 0.0, .lower_open = true, .unit = "forcing periods",
       .front_ends = FrontEnds::python},
      {.name = "max_reference_impacts", .type = OptionType::integer,
       .help = "impacts of the reference compared at most", .default_value = 20.0, .lower = 1,
       .unit = "impacts", .front_ends = FrontEnds::python},
      {.name = "repetitions", .type = OptionType::integer,
       .help = "timed repetitions per point (median)", .default_value = 1.0, .lower = 1,
       .front_ends = FrontEnds::python},
  };
}

Options reproduce_options() {
  return {
      {.name = "paper", .type = OptionType::text, .help = "the figure set: jin2003",
       .choices = {"jin2003"}, .front_ends = FrontEnds::cli, .positional = true,
       .required = true},
      scene_settings("KEY=VALUE, repeatable: a scene key of jin2003 (e_n, mu, integrator.rtol, "
                     "...)"),
      {.name = "models", .type = OptionType::text_list,
       .help = "impact models, comma-separated; NAME[:KEY=VALUE]... gives a model scene settings "
               "of its own; the first model with a slip sets Fig. 4(d)'s window",
       .default_value = string_view("paper,newton,rigid:radius=0.01:spin=free"),
       .front_ends = FrontEnds::cli, .comma_separated = true},
      {.name = "out", .type = OptionType::text, .help = "output directory",
       .default_value = string_view("notebooks_data/jin2003"), .front_ends = FrontEnds::cli},
      {.name = "threads", .type = OptionType::integer,
       .help = "worker threads (default: all cores)",
       .lower = 1, .upper = 1024, .front_ends = FrontEnds::cli},
      {.name = "quick", .type = OptionType::flag, .help = "coarse grids, for tests",
       .default_value = false, .front_ends = FrontEnds::cli},
      {.name = "no_plot", .type = OptionType::flag, .help = "write the data only, no PNGs",
       .default_value = false, .front_ends = FrontEnds::cli},
      quiet(),
  };
}

Options spectrum_options() {
  return {
      scene_argument("built-in scene name or path"),
      scene_settings("KEY=VALUE, repeatable"),
      output_directory(),
      quiet(),
      {.name = "transient", .type = OptionType::number, .help = "forcing periods discarded first",
       .default_value = 100.0, .lower = 0, .upper = 1e9, .unit = "forcing periods",
       .front_ends = FrontEnds::cli},
      {.name = "periods", .type = OptionType::integer, .help = "forcing periods analysed",
       .default_value = 64.0, .lower = 1, .upper = 1000000, .unit = "forcing periods",
       .front_ends = FrontEnds::cli},
      {.name = "samples_per_period", .type = OptionType::integer,
       .help = "samples per forcing period", .default_value = 64.0, .lower = 2, .upper = 100000,
       .front_ends = FrontEnds::cli},
  };
}

Options explore_options() {
  return {
      scene_argument("built-in scene name or path to a scene file (.toml)"),
      {.name = "port", .type = OptionType::integer,
       .help = "port on 127.0.0.1 to serve the page on; 0: any free one", .default_value = 0.0,
       .lower = 0, .upper = 65535},
  };
}

struct JobTable {
  string_view job;
  Options (*make)();
};

// every job with options, in the order job_names lists them
const std::array<JobTable, 13>& job_tables() {
  static constexpr std::array<JobTable, 13> tables = {{
      {"simulate", simulate_options},
      {"poincare", poincare_options},
      {"sweep", sweep_options},
      {"basins", basins_options},
      {"attractors", attractors_options},
      {"periodic", periodic_options},
      {"continue", continue_options},
      {"compare", compare_options},
      {"bench", bench_options},
      {"work_precision", work_precision_options},
      {"reproduce", reproduce_options},
      {"spectrum", spectrum_options},
      {"explore", explore_options},
  }};
  return tables;
}

}  // namespace

std::span<const OptionSpec> job_options(std::string_view job) {
  // every table built once, on first use
  static const std::vector<Options> tables = [] {
    std::vector<Options> built;
    for (const JobTable& table : job_tables()) built.push_back(table.make());
    return built;
  }();
  for (std::size_t k = 0; k < job_tables().size(); ++k)
    if (job_tables()[k].job == job) return tables[k];
  throw BadInput("job", std::string(job), "not a job with options");
}

std::span<const std::string_view> job_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> listed;
    for (const JobTable& table : job_tables()) listed.push_back(table.job);
    return listed;
  }();
  return names;
}

const OptionSpec& job_option(std::string_view job, std::string_view name) {
  const auto options = job_options(job);
  const auto found = std::find_if(options.begin(), options.end(),
                                  [&](const OptionSpec& spec) { return spec.name == name; });
  if (found == options.end())
    throw std::out_of_range("job " + std::string(job) + " has no option " + std::string(name));
  return *found;
}

std::string option_flag(std::string_view name) {
  std::string flag = "--" + std::string(name);
  std::replace(flag.begin() + 2, flag.end(), '_', '-');
  return flag;
}

std::string spell_options(std::string_view text,
                          const std::function<std::string(std::string_view)>& spell) {
  std::string spelled;
  std::size_t from = 0;
  while (from < text.size()) {
    const std::size_t open = text.find('`', from);
    const std::size_t close = open == string_view::npos ? open : text.find('`', open + 1);
    if (close == string_view::npos) break;
    spelled += text.substr(from, open - from);
    spelled += spell(text.substr(open + 1, close - open - 1));
    from = close + 1;
  }
  if (from < text.size()) spelled += text.substr(from);
  return spelled;
}

std::string mention(std::string_view name) { return "`" + std::string(name) + "`"; }

}  // namespace impactlab
