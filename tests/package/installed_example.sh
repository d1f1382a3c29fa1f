#!/usr/bin/env bash
# The installed package as a user meets it: `cmake --install` of the build tree to a temporary
# prefix, then examples/fold_of_cycles configured, built and run out of tree against that
# prefix alone. Fails if any step fails; the temporary directory goes in any case.
# Usage: installed_example.sh CMAKE BUILD_DIR EXAMPLE_SOURCE_DIR CXX_COMPILER
set -euo pipefail
cmake=$1 build=$2 example=$3 cxx=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

step() { echo "== $*"; }
step "install to $tmp/prefix"
"$cmake" --install "$build" --prefix "$tmp/prefix" > "$tmp/install.log" ||
  { cat "$tmp/install.log"; exit 1; }
# The package's files, wherever the build put its libdir (lib, lib64, lib/<multiarch>).
config=$(find "$tmp/prefix" -path '*/cmake/sympathy/sympathyConfig.cmake')
[[ -n "$config" ]] || { echo "not installed: sympathyConfig.cmake"; exit 1; }
for f in sympathyConfigVersion.cmake sympathyTargets.cmake FindSuiteSparse.cmake; do
  [[ -f "$(dirname "$config")/$f" ]] || { echo "not installed: $f"; exit 1; }
done
[[ -f "$tmp/prefix/include/sympathy/continuation/continuation.hpp" ]] ||
  { echo "not installed: the headers"; exit 1; }

step "configure the example against the prefix"
"$cmake" -S "$example" -B "$tmp/example-build" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="$cxx"
# It must have found the installed package, not some other sympathy.
found=$(sed -n 's/^sympathy_DIR:PATH=//p' "$tmp/example-build/CMakeCache.txt")
[[ "$found" == "$tmp/prefix/"* ]] || { echo "found sympathy at '$found', not in the prefix"; exit 1; }

step "build the example"
"$cmake" --build "$tmp/example-build"

step "run the example"
"$tmp/example-build/fold_of_cycles"

# An equation case file with the installed program, compiling against the installed headers only
# (SYMPATHY_INCLUDE_DIR: the prefix is temporary, not the configured CMAKE_INSTALL_PREFIX): they
# must be the ones the program was built with (their SHA-256s, recorded at configure time).
if [[ -x "$tmp/prefix/bin/sympathy" ]]; then
  step "the installed program on an equation case file, against the installed headers"
  SYMPATHY_INCLUDE_DIR="$tmp/prefix/include" SYMPATHY_CACHE_DIR="$tmp/cache" \
    "$tmp/prefix/bin/sympathy" orbit "$example/../../cases/examples/hopf.toml" > "$tmp/hopf.out"
  grep -q "system compiled in .* against the headers in $tmp/prefix/include " "$tmp/hopf.out" ||
    { cat "$tmp/hopf.out"; exit 1; }
  grep -q '^  period       6.28318530' "$tmp/hopf.out" || { cat "$tmp/hopf.out"; exit 1; }
  grep -q "$tmp/prefix/include" "$tmp/cache/"*.cpp 2>/dev/null && exit 1  # no paths in the source
  echo "ok: compiled against $tmp/prefix/include"
fi

# The Python package where `cmake --install` put it (PREFIX/lib/python3.X/dist-packages under a
# prefix other than /usr): imported from there alone and run on an equation case file.
init=$(find "$tmp/prefix" -path '*-packages/sympathy/__init__.py' | head -1)
if [[ -n "$init" ]]; then
  step "the installed Python package"
  site=$(dirname "$(dirname "$init")")
  for f in _options.py __init__.pyi py.typed; do
    [[ -f "$site/sympathy/$f" ]] || { echo "not installed: sympathy/$f"; exit 1; }
  done
  ls "$site"/sympathy/_core*.so > /dev/null || { echo "not installed: sympathy/_core"; exit 1; }
  (cd "$tmp" && PYTHONPATH="$site" SYMPATHY_INCLUDE_DIR="$tmp/prefix/include" \
     SYMPATHY_CACHE_DIR="$tmp/cache" /usr/bin/python3 -c "
import sympathy
assert sympathy.__file__.startswith('$site'), sympathy.__file__
orbit = sympathy.orbit('$example/../../cases/examples/hopf.toml')
assert abs(orbit.period - 6.283185307) < 1e-8, orbit.period
print('ok: sympathy imported from', '$site', 'period', orbit.period)")
fi
