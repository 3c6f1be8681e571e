// A boundary of a continuation in terms of the scene: `value(scene)` changes
// sign where the branch crosses it, as a function of the continued key alone
// (the pendulum's V0·ω = g, below which no contact phase can exist). The
// continuation reports and locates each crossing (ParameterBoundary,
// analysis/continuation_problem.hpp); `name` is its type in points.csv.
#pragma once

#include <string>

namespace impactlab {

struct Scene;

struct SceneBoundary {
  std::string name, note;
  double (*value)(const Scene& scene) = nullptr;
};

}  // namespace impactlab
