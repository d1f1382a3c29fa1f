#!/usr/bin/env bash
# sympathy inside another project: a parent with targets of its own named `core` and `cases`
# (sympathy's are sympathy_core, sympathy_cases: no clash) brings sympathy in with
# add_subdirectory and links sympathy::continuation. Checks that sympathy's tests are off there,
# that the parent's build type, standard and warnings are its own. Configuring generates the
# parent's link lines, so sympathy::continuation's dependencies are resolved from the parent too.
# With --build it also builds and runs the parent's program (examples/fold_of_cycles/main.cpp);
# that compiles sympathy's engine again (about 2 minutes on two cores), so the ctest test
# (package.add_subdirectory) only configures. The temporary directory goes in any case.
# Usage: add_subdirectory.sh CMAKE SOURCE_DIR CXX_COMPILER [--build [JOBS]]
set -euo pipefail
cmake=$1 src=$2 cxx=$3 build=${4:-} jobs=${5:-2}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

mkdir -p "$tmp/parent"
cat > "$tmp/parent/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.25)
project(parent LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_EXPORT_COMPILE_COMMANDS ON)
add_subdirectory("$src" sympathy)
add_library(core core.cpp)
add_library(cases cases.cpp)
add_executable(app "$src/examples/fold_of_cycles/main.cpp")
target_link_libraries(app PRIVATE sympathy::continuation core cases)
CMAKE
echo 'int parent_core() { return 1; }' > "$tmp/parent/core.cpp"
echo 'int parent_cases() { return 2; }' > "$tmp/parent/cases.cpp"

echo "== configure the parent"
"$cmake" -S "$tmp/parent" -B "$tmp/build" -DCMAKE_CXX_COMPILER="$cxx" > "$tmp/configure.log" ||
  { cat "$tmp/configure.log"; exit 1; }
cache=$tmp/build/CMakeCache.txt
grep -q '^SYMPATHY_BUILD_TESTS:BOOL=OFF$' "$cache" || { echo "sympathy's tests are on"; exit 1; }
grep -q '^CMAKE_BUILD_TYPE:STRING=$' "$cache" || { echo "the parent's build type was set"; exit 1; }
if [[ -e "$tmp/build/sympathy/tests" ]]; then echo "sympathy's tests were configured"; exit 1; fi
command_of() {  # the compile command of a source file, from compile_commands.json
  grep "\"command\": .*$1\"" "$tmp/build/compile_commands.json" || { echo "no command for $1"; exit 1; }
}
parent_core=$(command_of '/parent/core.cpp')
sympathy_core=$(command_of '/core/flow.cpp')
[[ "$parent_core" != *++20* && "$parent_core" != *-Wall* ]] ||
  { echo "the parent's own target got sympathy's settings: $parent_core"; exit 1; }
[[ "$sympathy_core" == *-std=c++20* && "$sympathy_core" == *-Wall* ]] ||
  { echo "sympathy's target lacks its settings: $sympathy_core"; exit 1; }

[[ "$build" == --build ]] || { echo "configured; not built (no --build)"; exit 0; }
echo "== build the parent's program (and sympathy's engine with it)"
"$cmake" --build "$tmp/build" --target app -j "$jobs" > "$tmp/build.log" ||
  { cat "$tmp/build.log"; exit 1; }
echo "== run it"
"$tmp/build/app"
