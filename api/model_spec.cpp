// A model specification set on a scene (model_spec.hpp).
#include <impactlab/api/model_spec.hpp>

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include <impactlab/api/scene_loading.hpp>

namespace impactlab {

void apply_model(Scene& scene, std::string_view model_spec) {
  std::size_t start = 0;
  bool first = true;
  while (start <= model_spec.size()) {
    const std::size_t end = std::min(model_spec.find(':', start), model_spec.size());
    const std::string_view part = model_spec.substr(start, end - start);
    apply_override(scene, first ? fmt::format("model={}", part) : std::string(part));
    first = false;
    start = end + 1;
  }
}

}  // namespace impactlab
