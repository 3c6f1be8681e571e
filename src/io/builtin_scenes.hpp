// The built-in scenes: the scene files under oscillators/*/ compiled into the
// library at build time (cmake/embed_scenes.cmake), named after their file.
#pragma once

#include <string_view>
#include <vector>

namespace impactlab {

struct BuiltinScene {
  std::string_view name;  // file name without .toml
  std::string_view text;  // the scene file's TOML text
};

const std::vector<BuiltinScene>& builtin_scenes();

}  // namespace impactlab
