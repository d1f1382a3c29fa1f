# Finds SuiteSparse (Debian's libsuitesparse-dev ships no CMake package) and defines
# SuiteSparse::<component> imported targets for the components asked for, e.g.
#   find_package(SuiteSparse REQUIRED COMPONENTS umfpack klu)
include(FindPackageHandleStandardArgs)

find_path(SuiteSparse_INCLUDE_DIR SuiteSparse_config.h PATH_SUFFIXES suitesparse)
find_library(SuiteSparse_config_LIBRARY suitesparseconfig)
set(_ss_required SuiteSparse_INCLUDE_DIR SuiteSparse_config_LIBRARY)

if(SuiteSparse_config_LIBRARY AND NOT TARGET SuiteSparse::config)
  add_library(SuiteSparse::config UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::config PROPERTIES
    IMPORTED_LOCATION "${SuiteSparse_config_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
endif()

foreach(_c IN LISTS SuiteSparse_FIND_COMPONENTS)
  find_library(SuiteSparse_${_c}_LIBRARY ${_c})
  list(APPEND _ss_required SuiteSparse_${_c}_LIBRARY)
  if(SuiteSparse_${_c}_LIBRARY)
    set(SuiteSparse_${_c}_FOUND TRUE)
    if(NOT TARGET SuiteSparse::${_c})
      add_library(SuiteSparse::${_c} UNKNOWN IMPORTED)
      set_target_properties(SuiteSparse::${_c} PROPERTIES
        IMPORTED_LOCATION "${SuiteSparse_${_c}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}"
        INTERFACE_LINK_LIBRARIES SuiteSparse::config)
    endif()
  endif()
endforeach()

find_package_handle_standard_args(SuiteSparse REQUIRED_VARS ${_ss_required} HANDLE_COMPONENTS)
