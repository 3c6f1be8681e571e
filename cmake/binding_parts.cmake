# impactlab_binding_parts(<variable> FUNCTION <name> DEFINITION <header> PARTS <n>)
# generates the n units that compile the function template <name> over the
# bindings, part k for the bindings whose index i has i % n == k
# (api/binding_parts.hpp), and sets <variable> to their paths. <header>, under
# the project's include prefix (api/...), defines the template.
function(impactlab_binding_parts variable)
  cmake_parse_arguments(binding "" "FUNCTION;DEFINITION;PARTS" "" ${ARGN})
  set(IMPACTLAB_FUNCTION ${binding_FUNCTION})
  set(IMPACTLAB_DEFINITION ${binding_DEFINITION})
  set(IMPACTLAB_PARTS ${binding_PARTS})
  set(sources)
  math(EXPR last_part "${binding_PARTS} - 1")
  foreach(IMPACTLAB_PART RANGE ${last_part})
    set(source ${CMAKE_CURRENT_BINARY_DIR}/generated/${binding_FUNCTION}_part_${IMPACTLAB_PART}.cpp)
    configure_file(${PROJECT_SOURCE_DIR}/cmake/binding_part.cpp.in ${source} @ONLY)
    list(APPEND sources ${source})
  endforeach()
  set(${variable} ${sources} PARENT_SCOPE)
endfunction()
