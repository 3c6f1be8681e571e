// A model specification: an impact model's name, then scene settings of its
// own after colons ("rigid:radius=0.01:spin=free"), as `reproduce --models`
// and `compare --models` take them.
#pragma once

#include <string_view>

#include <impactlab/io/scene.hpp>

namespace impactlab {

// Sets a model specification on a scene: "NAME[:KEY=VALUE]...", the model
// name and then scene keys for that model alone (BadInput names a bad one).
void apply_model(Scene& scene, std::string_view model_spec);

}  // namespace impactlab
