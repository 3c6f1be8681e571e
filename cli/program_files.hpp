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

// The Python that runs the plot scripts: $IMPACTLAB_PYTHON where it is set
// and not empty, else /usr/bin/python3 (Debian's, with NumPy and matplotlib;
// a python3 earlier on PATH may lack them).
std::filesystem::path plot_python();

}  // namespace impactlab::cli
