#include "program_files.hpp"

#include <cstdlib>

#include <impactlab/platform/program_location.hpp>

namespace impactlab::cli {

std::filesystem::path program_file(std::string_view relative) {
  const std::filesystem::path folder = running_program_path().parent_path();
  const std::filesystem::path installed = folder / ".." / "share" / "impactlab" / relative;
  const std::filesystem::path built = folder / "share" / "impactlab" / relative;
  if (std::filesystem::exists(installed)) return installed.lexically_normal();
  if (std::filesystem::exists(built)) return built;
  return installed.lexically_normal();
}

std::filesystem::path plot_python() {
  const char* chosen = std::getenv("IMPACTLAB_PYTHON");
  return chosen != nullptr && *chosen != '\0' ? std::filesystem::path(chosen)
                                               : std::filesystem::path("/usr/bin/python3");
}

}  // namespace impactlab::cli
