// A two-parameter continuation job for the tests: the curve of `type` in
// (key, key2) from the branch key = from → to run at key2 = from2, followed
// to key2 = to2 (the options --param, --param2 and --curve).
#pragma once

#include <string>

#include <impactlab/analysis/continuation.hpp>

namespace impactlab::testing {

inline ContinuationJob curve_job(const std::string& key, double from, double to,
                                 const std::string& key2, double from2, double to2,
                                 CurveType type) {
  ContinuationJob job;
  job.parameter = key;
  job.from = from;
  job.to = to;
  job.second_parameter = key2;
  job.second_from = from2;
  job.second_to = to2;
  job.curve_type = type;
  return job;
}

}  // namespace impactlab::testing
