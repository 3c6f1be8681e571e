// Options shared by the commands that run a scene onto a Poincaré section
// (poincare, sweep): the scene and its overrides, the section, the transient
// and the number of points, the output directory, and the plot.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <impactlab/analysis/section.hpp>
#include "command.hpp"
#include "table_options.hpp"

namespace impactlab::cli {

// The values as given; their defaults come from the job's option table.
struct SectionOptions {
  SceneOptions scene;       // scene, --set, --out, --quiet (its other fields unused)
  std::string section;      // strobe[:PHASE] | impact[:WALL]
  double transient = 0.0;   // forcing periods discarded, where given (transient_option)
  double max_transient = 0.0;  // the settling transient's most forcing periods
  CLI::Option* transient_option = nullptr;
  std::uint64_t transient_impacts = 0;
  std::uint64_t points = 0;
  bool plot = false;

  // adds the scene arguments and the section options of the job's table
  void add_to(TableOptions& table);
  // the section request (BadInput on a malformed --section)
  [[nodiscard]] SectionRequest request() const;
};

// Runs scripts/plot_sweep.py with /usr/bin/python3 to write `png` from
// `csv`; prints a warning and returns false where python3, matplotlib or the
// script is missing (the data files stay).
bool plot_with_python(const std::string& kind, const std::filesystem::path& csv,
                      const std::filesystem::path& png, const std::vector<std::string>& extra);

}  // namespace impactlab::cli
