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
  sympathy_target_sanitizers(${target})
endfunction()

# SYMPATHY_SANITIZE (and SYMPATHY_FUZZ): the sanitizers on this target's own sources, and at link
# time on the target and on whatever links it (a static library instrumented by ASan needs the
# ASan runtime in the program), so the flags travel with the libraries to the tests and the CLI.
function(sympathy_target_sanitizers target)
  if(NOT SYMPATHY_SANITIZE AND NOT SYMPATHY_FUZZ)
    return()
  endif()
  set(flags -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  set(compile_flags ${flags})
  if(SYMPATHY_FUZZ)
    # The coverage instrumentation libFuzzer steers by, without its main() (the fuzz targets link
    # -fsanitize=fuzzer themselves, see tests/fuzz/CMakeLists.txt).
    list(APPEND compile_flags -fsanitize=fuzzer-no-link)
  endif()
  target_compile_options(${target} PRIVATE ${compile_flags})
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "EXECUTABLE")
    target_link_options(${target} PRIVATE ${flags})
  else()
    target_link_options(${target} PUBLIC ${flags})
  endif()
endfunction()

# Static libraries compiled position-independent, so that a shared object can link them: the Python
# module (python/), or a user's plug-in. -fno-semantic-interposition keeps what -fPIC alone takes
# from GCC (inlining and direct calls between a library's own functions, which -fPIE allows): the
# libraries are never interposed.
function(sympathy_position_independent target)
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_compile_options(${target} PRIVATE $<$<CXX_COMPILER_ID:GNU>:-fno-semantic-interposition>)
endfunction()

# sympathy_add_library(<name> <source>...): the library sympathy_<name>, used in the tree and
# by an installed package alike as sympathy::<name> (an ALIAS here, the exported name there),
# with the public headers of include/ (include/sympathy/<layer>/...).
function(sympathy_add_library name)
  add_library(sympathy_${name} ${ARGN})
  add_library(sympathy::${name} ALIAS sympathy_${name})
  set_target_properties(sympathy_${name} PROPERTIES EXPORT_NAME ${name})
  sympathy_position_independent(sympathy_${name})
  target_include_directories(sympathy_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  sympathy_target_defaults(sympathy_${name})
endfunction()
