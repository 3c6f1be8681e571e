// The parts an analysis is compiled in (api/binding_parts.hpp): for every
// number of parts, each binding of BuiltinBindings is in exactly one part,
// part k holding the bindings at the indices i with i mod parts = k, in their
// order; parts beyond the number of bindings are empty.
#include <cstddef>
#include <typeindex>
#include <typeinfo>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <impactlab/api/binding_parts.hpp>

#include "support/test_support.hpp"

namespace impactlab {
namespace IMPACTLAB_TEST_FILE_SCOPE {

template <class... Bindings>
std::vector<std::type_index> types_of(BindingList<Bindings...>) {
  return {std::type_index(typeid(Bindings))...};
}

// the parts' bindings, part after part, for `Parts` parts
template <std::size_t Parts, std::size_t... Part>
std::vector<std::vector<std::type_index>> parts_of(std::index_sequence<Part...>) {
  return {types_of(BindingsOfPart<Part, Parts>{})...};
}

template <std::size_t Parts>
void expect_a_partition_by_index() {
  const std::vector<std::type_index> all = types_of(BuiltinBindings{});
  const auto parts = parts_of<Parts>(std::make_index_sequence<Parts>{});
  for (std::size_t part = 0; part < Parts; ++part) {
    std::vector<std::type_index> expected;
    for (std::size_t i = part; i < all.size(); i += Parts) expected.push_back(all[i]);
    EXPECT_EQ(parts[part], expected) << "part " << part << " of " << Parts;
  }
}

TEST(BindingParts, EveryBindingIsInTheOnePartOfItsIndex) {
  expect_a_partition_by_index<1>();
  expect_a_partition_by_index<2>();
  expect_a_partition_by_index<3>();
  expect_a_partition_by_index<4>();
  expect_a_partition_by_index<7>();
  // more parts than bindings: the last ones empty
  expect_a_partition_by_index<13>();
}

}  // namespace IMPACTLAB_TEST_FILE_SCOPE
}  // namespace impactlab
