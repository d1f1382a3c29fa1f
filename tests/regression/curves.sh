#!/usr/bin/env bash
# The two-parameter curves held by the regression goldens (tests/regression/goldens.json,
# "curves"): the row setup's anti-phase BP curve in (k, c) and its first NS curve in (k, M),
# each from Table II to a window edge in the second parameter, where its end is compared; and a
# fold curve, AUTO-07p's abc (cases/examples/abc.toml) from its fold of cycles at p1 = 0.2119
# (p3 = 1.55) to p3 = 1.56 (its cache in DIR, never the user's).
# Written to DIR/curve-NAME.json. Used by ctest (label regression) and scripts/update_goldens.
# usage: tests/regression/curves.sh SYMPATHY_BINARY SOURCE_DIR DIR
set -euo pipefail
bin=$1 src=$2 dir=$3
mkdir -p "$dir"
row2=$src/cases/row2.toml
"$bin" curve "$row2" --start anti-phase --param k --from 45 --to 49 --event BP1 \
  --second c --second-from 0.0185 --second-to 0.06 --quiet --json "$dir/curve-bp_kc.json"
"$bin" curve "$row2" --start anti-phase --param k --from 48 --to 55 --event NS1 \
  --second M --second-from 0.3778 --second-to 0.40 --quiet --json "$dir/curve-ns_km.json"
SYMPATHY_CACHE_DIR="$dir/cache" "$bin" curve "$src/cases/examples/abc.toml" --param p1 \
  --from 0.25 --to 0.205 --event LP1 --second p3 --second-from 1.55 --second-to 1.56 --quiet \
  --json "$dir/curve-lp_abc.json"
