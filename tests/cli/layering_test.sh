#!/bin/bash
# The front ends stand on the application layer alone (issue 34): the command line (cases/cli/)
# and the Python module (python/) include no engine header (sympathy/...: core, floquet,
# continuation, cases) and the application layer (cases/app/) includes nothing of the command
# line; the libraries link accordingly (LINKS: "TARGET=LIBRARIES" as CMake holds them).
# Usage: layering_test.sh SOURCE_DIR LINKS...
set -u
src=$1; shift
. "$(dirname "$0")/check.sh"

includes() {  # the files under $1 (C++ sources and headers) whose #include matches $2
  grep -lE "^[[:space:]]*#[[:space:]]*include[[:space:]]*\"$2" \
    "$1"/*.cpp "$1"/*.hpp 2>/dev/null
}
none() { local found; found=$(includes "$1" "$2"); [ -z "$found" ] || { echo "$found"; return 1; }; }

check "the command line includes no engine header" none "$src/cases/cli" "sympathy/"
check "the Python module includes no command-line header" none "$src/python" "cases/cli/"
check "the application layer includes no command-line header" none "$src/cases/app" "cases/cli/"
# The test's own check: a planted include is found (the pattern is not one that never matches).
planted=$(mktemp -d)
printf '#include "sympathy/core/flow.hpp"\n' > "$planted/x.cpp"
check "a planted engine include is found" test -n "$(includes "$planted" sympathy/)"
rm -rf "$planted"

for link in "$@"; do
  target=${link%%=*} libraries=${link#*=}
  check "$target links only the application layer ($libraries)" test "$libraries" = sympathy_app
done
exit "$failures"
