#include <impactlab/platform/program_location.hpp>

#include <system_error>

namespace impactlab {

std::filesystem::path running_program_path() {
  std::error_code error;
  std::filesystem::path path = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return {};
  return path;
}

}  // namespace impactlab
