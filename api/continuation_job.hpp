// `continue` as a job that any front end runs: its options as the user gives
// them (the CLI's flags, Python's keywords; defaults from
// api/job_options.hpp's "continue" table) made into the ContinuationJob that
// continue_orbit (api/scene_jobs.hpp) runs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <impactlab/analysis/continuation.hpp>

namespace impactlab {

// The period doublings that `switch` follows: the cascade, up to period 8n.
constexpr int doublings_followed = 3;

struct ContinueOptions {
  std::string param;                  // NAME=FROM:TO: the scene key continued
  std::string param2;                 // NAME=FROM:TO: a two-parameter curve; empty: none
  std::string curve;  // fold | period_doubling | grazing | contact_onset | contact_end; empty: the first located
  int period = 1;                     // n: forcing periods of the orbit
  std::string section = "strobe";     // strobe[:PHASE] | impact:WALL
  bool switch_doubling = false;       // follow the doubling cascade (`switch`)
  std::vector<double> start;          // N numbers on the section; empty: the transient's end
  // the numbers' defaults are the library's own (analysis/continuation.hpp)
  double transient = ContinuationJob{}.transient_periods;  // forcing periods run for the start
  int max_points = ContinuationRequest{}.max_points;       // points per branch
  double tolerance = ContinuationRequest{}.tolerance;      // |P^n(x) - x| / (1 + |x|)
  double max_step = ContinuationRequest{}.max_step;        // largest arclength step; 0: 1/50 of the range
  bool no_normal_forms = false;  // skip the normal form at each located grazing point
  // `all`: every orbit of the period at FROM (periodic --all's), each continued
  bool all = false;
  int starts = 20;               // starts drawn from the box
  std::vector<std::string> box;  // KEY=FROM:TO each; empty: the default box
  std::uint64_t seed = 1;        // of the starts
};

// A scene key and its range, NAME=FROM:TO.
struct KeyRange {
  std::string name;
  double from = 0.0, to = 0.0;
};

// NAME=FROM:TO, FROM and TO finite and different (the key and its range are
// checked by continue_orbit). BadInput names `option`.
KeyRange parse_parameter_range(const std::string& text, const std::string& option);

// The job the options describe. BadInput (named by the option) for a
// malformed range or section, a value outside the option's range, fewer than
// two start numbers, or `curve` without `param2` or naming no curve type.
ContinuationJob continuation_job(const ContinueOptions& options);

}  // namespace impactlab
