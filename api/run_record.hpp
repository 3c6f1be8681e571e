// What meta.json records of one `simulate` run: the scene, the model, the
// integrator, the time span and termination, the counters, the derived
// quantities and the column units. The CLI adds the command line, the time
// of writing and the file list; the Python module returns it as `meta`.
#pragma once

#include <nlohmann/json.hpp>

#include <impactlab/io/run_output.hpp>
#include <impactlab/io/scene.hpp>

namespace impactlab {

nlohmann::json run_record(const Scene& scene, const RunOutput& output);

}  // namespace impactlab
