# How sympathy's own targets are set up. Everything here is per target, so that a parent
# project that brings sympathy in with add_subdirectory keeps its own standard and warnings.

# C++20 (propagated to whoever links the target, as its headers need it), no compiler
# extensions, and the project's warnings on this target's own sources only.
function(sympathy_target_defaults target)
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "EXECUTABLE")
    target_compile_features(${target} PRIVATE cxx_std_20)
  else()
    target_compile_features(${target} PUBLIC cxx_std_20)
  endif()
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE
    $<$<CXX_COMPILER_ID:GNU,Clang,AppleClang>:-Wall -Wextra -Wpedantic>)
endfunction()

# sympathy_add_library(<name> <source>...): the library sympathy_<name>, used in the tree and
# by an installed package alike as sympathy::<name> (an ALIAS here, the exported name there),
# with the public headers of include/ (include/sympathy/<layer>/...).
function(sympathy_add_library name)
  add_library(sympathy_${name} ${ARGN})
  add_library(sympathy::${name} ALIAS sympathy_${name})
  set_target_properties(sympathy_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(sympathy_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  sympathy_target_defaults(sympathy_${name})
endfunction()
