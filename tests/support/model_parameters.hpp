// A model file's parameter values for a test: its defaults, some replaced.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <impactlab/oscillators/model_file/compiled_model.hpp>

namespace impactlab::testing {

// The parameter values in the model's order, from name = value pairs; the
// model's defaults for the others.
inline std::vector<double> model_parameter_values(
    const CompiledModel& model, const std::vector<std::pair<std::string, double>>& given = {}) {
  std::vector<double> p;
  for (const auto& parameter : model.parameters) {
    double value = parameter.default_value;
    for (const auto& [name, v] : given)
      if (name == parameter.name) value = v;
    p.push_back(value);
  }
  return p;
}

}  // namespace impactlab::testing
