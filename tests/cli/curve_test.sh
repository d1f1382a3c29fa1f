#!/usr/bin/env bash
# The curve command end to end: a BP curve of the anti-phase orbit in (k, c) from a saved branch,
# its CSV and JSON, and bad requests refused before any work.
# Usage: curve_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
json() { /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }
row2=$src/cases/row2.toml

"$bin" continue "$row2" --start anti-phase --param k --from 46 --to 48 --quiet \
  --json "$work/anti.json" > "$work/anti.out" 2>&1
check "the parent branch exits 0" test $? -eq 0

"$bin" curve "$row2" --start anti-phase --param k --from 40 --to 55 --parent "$work/anti.json" \
  --event BP1 --second c --second-from 0.0185 --second-to 0.03 \
  --csv "$work/bp.csv" --json "$work/bp.json" > "$work/bp.out" 2> "$work/bp.err"
check "curve exits 0" test $? -eq 0
check "run time printed" grep -q 'run time' "$work/bp.out"
check "progress lines on stderr" grep -q '^  \[   1\] k = ' "$work/bp.err"
check "JSON: a BP curve in k and c, born at the branch's BP" \
  test "$(json "$work/bp.json" "j['kind'] == 'BP' and j['first'] == 'k' and j['second'] == 'c' and j['origin'].startswith('BP at k = 47.06')")" = True
check "CSV has a row per point" test "$(($(wc -l < "$work/bp.csv") - 1))" -eq "$(json "$work/bp.json" "len(j['points'])")"
check "CSV header" grep -q '^index,k,c,period,stability' "$work/bp.csv"
check "every point: the breaking multiplier within 1e-8 of 1, trivial error below 1e-8" \
  test "$(json "$work/bp.json" "all(abs(complex(*p['critical'][0]) - 1) < 1e-8 and p['trivial_multiplier_error'] < 1e-8 for p in j['points'])")" = True
check "the last point on the window's edge, c = 0.03 exactly, k below the Table II BP" \
  test "$(json "$work/bp.json" "j['points'][-1]['second'] == 0.03 and j['points'][-1]['first'] < 47.06")" = True

# Bad requests: named, exit 2, before any curve work.
"$bin" curve "$row2" --start anti-phase --param k --from 40 --to 55 --parent "$work/anti.json" \
  --event NS3 --second c --second-from 0 --second-to 0.1 > /dev/null 2> "$work/bad.err"
check "an event not on the branch exits 2" test $? -eq 2
check "... and lists the branch's events" grep -q -- "--event NS3: the branch has no such event; it has BP1 at 47.06" "$work/bad.err"
"$bin" curve "$row2" --start anti-phase --param k --from 40 --to 55 --parent "$work/anti.json" \
  --event XY1 --second c --second-from 0 --second-to 0.1 > /dev/null 2> "$work/bad.err"
check "an unknown event kind exits 2, saying what is expected" \
  grep -q -- "--event XY1: expected a located bifurcation, LP, BP, PD or NS" "$work/bad.err"
"$bin" curve "$row2" --start anti-phase --param k --from 40 --to 55 --parent "$work/anti.json" \
  --event BP1 --second k --second-from 0 --second-to 0.1 > /dev/null 2> "$work/bad.err"
check "a second parameter equal to the first is refused" \
  grep -q -- "--second k: expected a parameter other than --param" "$work/bad.err"
"$bin" curve "$row2" --start anti-phase --param k --from 40 --to 55 --parent "$work/anti.json" \
  --event BP1 --second c --second-from 0.1 --second-to 0.2 > /dev/null 2> "$work/bad.err"
check "a window without the event exits 2" test $? -eq 2
check "... naming the window and the branch's value" \
  grep -q -- "--second-from, --second-to: the window 0.1 to 0.2 does not contain the event (c = 0.0185 on the branch)" "$work/bad.err"
"$bin" curve "$row2" --start anti-phase --param k --from 40 --to 55 --parent "$work/anti.json" \
  --event BP1 --second c --second-from -0.1 --second-to 0.2 > /dev/null 2> "$work/bad.err"
check "a window outside the parameter's domain is refused" grep -q -- "--second-from, --second-to: " "$work/bad.err"
exit "$failures"
