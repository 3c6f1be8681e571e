#include <impactlab/api/continuation_job.hpp>

#include <cmath>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include <impactlab/api/job_options.hpp>
#include <impactlab/api/scene_jobs.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace {

// a whole-number option within the range its table row states
void check_whole(const std::string& name, int value) {
  const OptionSpec& spec = job_option("continue", name);
  if (value < spec.lower || value > spec.upper)
    throw BadInput(name, std::to_string(value),
                   fmt::format("expected {} to {}", spec.lower, spec.upper));
}

}  // namespace

KeyRange parse_parameter_range(const std::string& text, const std::string& option) {
  const auto bad = [&](const std::string& why) { return BadInput(option, text, why); };
  const auto equals = text.find('=');
  const auto colon = text.find(':', equals == std::string::npos ? 0 : equals);
  if (equals == std::string::npos || equals == 0 || colon == std::string::npos ||
      text.find(':', colon + 1) != std::string::npos)
    throw bad("expected NAME=FROM:TO");
  KeyRange range{text.substr(0, equals)};
  const std::string from = text.substr(equals + 1, colon - equals - 1), to = text.substr(colon + 1);
  char* end = nullptr;
  range.from = std::strtod(from.c_str(), &end);
  const bool from_ok = !from.empty() && *end == '\0' && std::isfinite(range.from);
  range.to = std::strtod(to.c_str(), &end);
  const bool to_ok = !to.empty() && *end == '\0' && std::isfinite(range.to);
  if (!from_ok || !to_ok) throw bad("FROM and TO must be finite numbers");
  if (range.from == range.to) throw bad("FROM and TO must differ");
  return range;
}

ContinuationJob continuation_job(const ContinueOptions& options) {
  const KeyRange range = parse_parameter_range(options.param, "param");
  const bool two_parameter = !options.param2.empty();
  const KeyRange range2 =
      two_parameter ? parse_parameter_range(options.param2, "param2") : KeyRange{};
  if (!options.curve.empty() && !two_parameter)
    throw BadInput("curve", options.curve, "needs " + mention("param2"));
  const std::optional<CurveType> curve_type = parse_curve_type(options.curve);
  if (!options.curve.empty() && !curve_type)
    throw BadInput("curve", options.curve,
                   "expected fold, period_doubling, grazing, contact_onset, contact_end, "
                   "contact_boundary, neimark_sacker or chatter_onset");
  check_whole("period", options.period);
  check_whole("max_points", options.max_points);
  const OptionSpec& transient = job_option("continue", "transient");
  if (!(options.transient >= transient.lower && options.transient <= transient.upper))
    throw BadInput("transient", fmt::format("{}", options.transient),
                   fmt::format("expected {} to {}", transient.lower, transient.upper));
  if (!options.start.empty() && options.start.size() < 2)
    throw BadInput("start", std::to_string(options.start.size()) + " numbers",
                   "expected Q,QDOT (a model file: its N states)");

  ContinuationJob job;
  job.parameter = range.name;
  job.from = range.from;
  job.to = range.to;
  job.period = options.period;
  job.transient_periods = options.transient;
  job.doublings = options.switch_doubling ? doublings_followed : 0;
  if (two_parameter) {
    job.second_parameter = range2.name;
    job.second_from = range2.from;
    job.second_to = range2.to;
    job.curve_type = curve_type;
  }
  set_continuation_section(job, options.section, "section");
  if (!options.start.empty()) {
    job.has_start = true;
    job.start = options.start;
  }
  job.numerics.max_points = options.max_points;
  job.numerics.tolerance = options.tolerance;
  job.numerics.max_step = options.max_step;
  job.numerics.normal_forms = !options.no_normal_forms;
  if (options.max_step > 0.0) job.numerics.initial_step = options.max_step;
  return job;
}

}  // namespace impactlab
