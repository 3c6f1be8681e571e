// An analysis too large to compile for every binding in one translation
// unit is compiled in parts: its function template over the binding is
// declared in one header, defined in another, and the build generates
// `parts` units (cmake/binding_part.cpp.in), unit k compiling it for the
// bindings of BuiltinBindings whose index i has i % parts == k. Neither the
// build nor the analysis lists the bindings: a new one lands in a part by its
// index. The dispatcher (api/<analysis>_of_scene.cpp) sees the declaration
// only; a binding no part compiled fails to link, naming it.
#pragma once

#include <cstddef>
#include <type_traits>

#include <impactlab/api/builtin_bindings.hpp>

namespace impactlab {

namespace detail {

template <std::size_t Part, std::size_t Parts, std::size_t Index, class Chosen, class Rest>
struct BindingsOfPart;

template <std::size_t Part, std::size_t Parts, std::size_t Index, class... Chosen>
struct BindingsOfPart<Part, Parts, Index, BindingList<Chosen...>, BindingList<>> {
  using type = BindingList<Chosen...>;
};

template <std::size_t Part, std::size_t Parts, std::size_t Index, class... Chosen, class First,
          class... Rest>
struct BindingsOfPart<Part, Parts, Index, BindingList<Chosen...>, BindingList<First, Rest...>> {
  using type = typename BindingsOfPart<
      Part, Parts, Index + 1,
      std::conditional_t<Index % Parts == Part, BindingList<Chosen..., First>,
                         BindingList<Chosen...>>,
      BindingList<Rest...>>::type;
};

}  // namespace detail

// The bindings of BuiltinBindings at the indices i with i % Parts == Part.
template <std::size_t Part, std::size_t Parts>
using BindingsOfPart =
    typename detail::BindingsOfPart<Part, Parts, 0, BindingList<>, BuiltinBindings>::type;

}  // namespace impactlab
