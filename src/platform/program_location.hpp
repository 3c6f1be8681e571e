// Where the running program's executable is, so that a program finds the
// files installed beside it (its plot scripts) without knowing where its
// source tree was.
#pragma once

#include <filesystem>

namespace impactlab {

// The absolute path of the running executable (Linux: /proc/self/exe); empty
// when the system cannot tell.
std::filesystem::path running_program_path();

}  // namespace impactlab
