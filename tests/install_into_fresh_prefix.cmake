# cmake -DBUILD_DIR=<impactlab build> -DPREFIX=<prefix> -P install_into_fresh_prefix.cmake
# Empties PREFIX, then installs the build into it, so that nothing a previous
# install left there (a header since removed) can hide a missing file.
foreach(required BUILD_DIR PREFIX)
  if(NOT ${required})
    message(FATAL_ERROR "${required} not given")
  endif()
endforeach()
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
                RESULT_VARIABLE install_status)
if(NOT install_status EQUAL 0)
  message(FATAL_ERROR "cmake --install ${BUILD_DIR} --prefix ${PREFIX} failed (${install_status})")
endif()
