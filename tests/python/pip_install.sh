#!/usr/bin/env bash
# pip install . as a Python user does it, with Debian's pip and no network: a fresh virtual
# environment (with the system's site packages, for NumPy), `pip install --no-build-isolation
# --no-index` of the repository, the extension taken from the CMake build directory BUILD_DIR
# (SYMPATHY_BUILD_DIR: nothing compiled a second time), then the package imported from the
# environment and run. The source tree gets no build files. About 4 s.
# Usage: pip_install.sh PYTHON SOURCE_DIR BUILD_DIR
set -euo pipefail
python=$1 source=$2 build=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$python" -m venv --system-site-packages "$tmp/env"
SYMPATHY_BUILD_DIR="$build" TMPDIR="$tmp" "$tmp/env/bin/pip" install --no-build-isolation \
  --no-index --quiet "$source" > "$tmp/pip.log" 2>&1 || { cat "$tmp/pip.log"; exit 1; }
cd "$tmp"
"$tmp/env/bin/python" - "$source" <<'PY'
import os, sys
import sympathy
source = sys.argv[1]
assert sympathy.__file__.startswith(os.path.join(sys.prefix, "lib")), sympathy.__file__
orbit = sympathy.orbit(os.path.join(source, "cases/examples/hopf.toml"))
assert abs(orbit.period - 6.283185307) < 1e-8, orbit.period
print("ok: pip-installed sympathy", sympathy.__file__, "period", orbit.period)
PY
# Nothing of the build in the source tree (setuptools' build/ and egg-info went to TMPDIR).
for junk in "$source/python/sympathy.egg-info" "$source/sympathy.egg-info" "$source/dist"; do
  [[ ! -e "$junk" ]] || { echo "pip install left $junk"; exit 1; }
done
