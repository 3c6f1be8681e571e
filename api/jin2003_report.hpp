// Writes the Fig. 4 reproduction of Jin, Hu & Bishop (2003) to a directory:
// fig4a.csv … fig4d.csv with JSON sidecars (units, grid, provenance),
// fig4a_values.csv and fig4b_values.csv (one row per parameter value),
// report.json (the derived ranges, machine-readable) and REPORT.md (the
// paper's ranges beside the toolkit's, with every difference explained).
// Every file appears only when complete.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include <impactlab/api/jin2003_reproduction.hpp>
#include <impactlab/io/output.hpp>

namespace impactlab {

// The paper's stated ranges where sliding is possible (Sec. 5).
struct PaperRanges {
  std::vector<ParameterRange> omega = {{6.6, 7.08}};               // rad/s, V0 = 1.5 m/s
  std::vector<ParameterRange> V0 = {{1.5, 1.6}, {3.971, 4.163}};  // m/s, ω = 7 rad/s
};

// provenance: command line, version, time, scene record; written into every
// sidecar. Every file goes into `run_files` and is committed with the others:
// all of them appear, or none.
void write_jin2003_outputs(const Jin2003Results& results, const Jin2003Settings& settings,
                           const Scene& scene, const nlohmann::json& provenance,
                           RunFiles& run_files);

}  // namespace impactlab
