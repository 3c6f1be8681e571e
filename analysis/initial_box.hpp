// A box of initial states sampled reproducibly: each key of the box takes a
// value drawn uniformly from its range, from a counter-based generator of
// (seed, parameter index, sample index, key index) alone, so that a sample
// is the same whatever the threads, the MPI ranks, the order the points run
// in, or an interruption and resume (analysis/sweep.hpp runs them; the
// attractors command of api/attractors_job.hpp samples them).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace impactlab {

// One key of the box: its values drawn uniformly from [from, to].
struct BoxRange {
  std::string key;  // a scene key, typically initial.<state>
  double from = 0.0, to = 0.0;
};

// A number uniform in [0, 1) (53 random bits) for one sample: splitmix64's
// finaliser over the four counters, chained, so that nearby counters give
// unrelated numbers.
double box_uniform(std::uint64_t seed, int point, int sample, int key);

// The value of box key `key` in sample `sample` at parameter index `point`.
double box_value(const BoxRange& range, std::uint64_t seed, int point, int sample, int key);

}  // namespace impactlab
