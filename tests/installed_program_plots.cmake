# cmake -DPREFIX=<prefix> -DOUT=<folder> -P installed_program_plots.cmake
# Runs the installed program (PREFIX/bin/impactlab) with --plot and fails
# unless the picture is drawn: the program finds its plot script beside
# itself (PREFIX/share/impactlab), not in the source tree it was built from.
foreach(required PREFIX OUT)
  if(NOT ${required})
    message(FATAL_ERROR "${required} not given")
  endif()
endforeach()
file(REMOVE_RECURSE ${OUT})
execute_process(
  COMMAND ${PREFIX}/bin/impactlab sweep linear_impact --param omega=2:2.2:3 --points 4
          --transient 10 --plot --quiet --out ${OUT}
  RESULT_VARIABLE status ERROR_VARIABLE errors)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the installed impactlab failed (${status}): ${errors}")
endif()
if(NOT EXISTS ${OUT}/bifurcation.png OR errors MATCHES "plot skipped")
  message(FATAL_ERROR "the installed impactlab drew no bifurcation.png: ${errors}")
endif()
if(NOT EXISTS ${PREFIX}/share/impactlab/scripts/plot_sweep.py)
  message(FATAL_ERROR "the plot script is not installed under ${PREFIX}/share/impactlab")
endif()
message(STATUS "the installed program drew ${OUT}/bifurcation.png")
