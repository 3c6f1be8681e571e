// The files the program runs beside itself (the plot scripts, bench's SciPy
// event loop, the Fig. 4 plot script), found relative to the executable:
// <bin>/../share/impactlab/ in an installed copy, <build>/share/impactlab/ in
// the build tree (CMakeLists.txt copies them there). Never the source tree:
// a moved or deleted clone does not break an installed program.
#pragma once

#include <filesystem>
#include <string_view>

namespace impactlab::cli {

// The path of `relative` (for example "scripts/plot_sweep.py") among the
// program's files; where it is in neither place, the installed location, so
// that a warning names where it was looked for.
std::filesystem::path program_file(std::string_view relative);

}  // namespace impactlab::cli
