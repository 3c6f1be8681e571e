// The one generic entry from a scene to its system: visit_scene(scene, f)
// finds the binding that runs the scene (api/scene_system.hpp), builds the
// system once and calls f(const SceneSystem<Binding>&). An analysis is a
// generic f; it is compiled once for each binding of builtin_bindings.hpp and
// never names an oscillator.
#pragma once

#include <string>
#include <type_traits>
#include <utility>

#include <impactlab/api/builtin_bindings.hpp>
#include <impactlab/api/oscillator_registry.hpp>
#include <impactlab/api/scene_system.hpp>
#include <impactlab/io/bad_input.hpp>

namespace impactlab {

namespace detail {

// Result: what f returns (the same for every binding)
template <class Result, class F, class First, class... Rest>
Result visit_bindings(const Scene& scene, F& f, BindingList<First, Rest...>) {
  if (First::matches(scene)) {
    const SceneSystem<First> bound(scene);
    return f(bound);
  }
  if constexpr (sizeof...(Rest) > 0) {
    return visit_bindings<Result>(scene, f, BindingList<Rest...>{});
  } else {
    // an oscillator the registry does not know: oscillator_entry's BadInput
    // names it and the known ones
    oscillator_entry(scene.oscillator);
    throw BadInput("oscillator", scene.oscillator, "no binding runs this oscillator");
  }
}

template <class F, class First, class... Rest>
auto result_of_visit(BindingList<First, Rest...>)
    -> std::invoke_result_t<F&, const SceneSystem<First>&>;

}  // namespace detail

// f(scene_system) for the scene's binding, every binding (every binding
// runs every analysis).
template <class F>
auto visit_scene(const Scene& scene, F&& f) {
  using Result = decltype(detail::result_of_visit<F>(BuiltinBindings{}));
  return detail::visit_bindings<Result>(scene, f, BuiltinBindings{});
}

}  // namespace impactlab
