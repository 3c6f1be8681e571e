# The libraries impactlab library links against, listed once. The build includes
# this file (each dependency REQUIRED), and so does the installed package
# (impactlabConfig.cmake, through find_dependency), so a program that calls
# find_package(impactlab) finds exactly what the library was built with.
# A new dependency is one more impactlab_dependency() line below.
#
#   impactlab_dependency(TARGET <imported target> PACKAGE <find_package arguments>...)
#   impactlab_dependency(TARGET <imported target> PKG_CONFIG <prefix> <module>)
#   impactlab_dependency(LIBRARIES <system libraries>...)   (nothing to find: ${CMAKE_DL_LIBS})
#
# IMPACTLAB_LINK_TARGETS collects the targets, in order, for target_link_libraries.
include(CMakeFindDependencyMacro)

set(IMPACTLAB_LINK_TARGETS)

# A macro, not a function: find_dependency's return() must leave this file
# (and so the package configuration) when a dependency is missing.
macro(impactlab_dependency)
  cmake_parse_arguments(_impactlab_dependency "" "TARGET" "PACKAGE;PKG_CONFIG;LIBRARIES" ${ARGN})
  if(_impactlab_dependency_PKG_CONFIG)
    list(GET _impactlab_dependency_PKG_CONFIG 0 _impactlab_dependency_prefix)
    list(GET _impactlab_dependency_PKG_CONFIG 1 _impactlab_dependency_module)
    if(IMPACTLAB_FINDING_INSTALLED_PACKAGE)
      find_dependency(PkgConfig)
      pkg_check_modules(${_impactlab_dependency_prefix} QUIET IMPORTED_TARGET
                        ${_impactlab_dependency_module})
      if(NOT ${_impactlab_dependency_prefix}_FOUND)
        set(impactlab_FOUND FALSE)
        set(impactlab_NOT_FOUND_MESSAGE
            "impactlab needs the pkg-config module ${_impactlab_dependency_module}, not found")
        return()
      endif()
    else()
      find_package(PkgConfig REQUIRED)
      pkg_check_modules(${_impactlab_dependency_prefix} REQUIRED IMPORTED_TARGET
                        ${_impactlab_dependency_module})
    endif()
  elseif(_impactlab_dependency_PACKAGE AND IMPACTLAB_FINDING_INSTALLED_PACKAGE)
    find_dependency(${_impactlab_dependency_PACKAGE})
  elseif(_impactlab_dependency_PACKAGE)
    find_package(${_impactlab_dependency_PACKAGE} REQUIRED)
  endif()
  list(APPEND IMPACTLAB_LINK_TARGETS ${_impactlab_dependency_TARGET}
       ${_impactlab_dependency_LIBRARIES})
endmacro()

impactlab_dependency(TARGET Eigen3::Eigen PACKAGE Eigen3 3.3 NO_MODULE)
impactlab_dependency(TARGET GSL::gsl PACKAGE GSL)
impactlab_dependency(TARGET Boost::boost PACKAGE Boost 1.74)
# the fibers of a batch's lanes (src/simulate/series_batch.cpp)
impactlab_dependency(TARGET Boost::context PACKAGE Boost 1.74 COMPONENTS context)
impactlab_dependency(TARGET nlohmann_json::nlohmann_json PACKAGE nlohmann_json 3.10)
impactlab_dependency(TARGET tomlplusplus::tomlplusplus PACKAGE tomlplusplus 3)
impactlab_dependency(TARGET fmt::fmt PACKAGE fmt)
impactlab_dependency(TARGET PkgConfig::FFTW3 PKG_CONFIG FFTW3 fftw3)
impactlab_dependency(TARGET OpenMP::OpenMP_CXX PACKAGE OpenMP COMPONENTS CXX)
# model sections of scene files: symbolic differentiation (oscillators/model_file/)
impactlab_dependency(TARGET PkgConfig::GINAC PKG_CONFIG GINAC ginac)
# the digest the model cache checks before it loads an object (src/platform/sha256.cpp)
impactlab_dependency(TARGET OpenSSL::Crypto PACKAGE OpenSSL COMPONENTS Crypto)
# and the compiled model loaded with dlopen
impactlab_dependency(LIBRARIES ${CMAKE_DL_LIBS})
