#!/usr/bin/env bash
# The curve command end to end: a BP curve of the anti-phase orbit in (k, c) from a saved branch,
# its CSV and JSON, and bad requests refused before any work.
# Usage: curve_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
json() { /usr/bin/python3 -c "import json,math,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }
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

# A restart from a point of the curve (AUTO's IRS on a two-parameter run): orbit --parent
# bp.json --from-point N starts at the point's orbit at both its parameters' values, and Newton
# gives back its period to 1e-9 relative and its breaking multiplier at +1 (to 1e-7: a BP curve's
# point, corrected without the curve's extra equation).
mid=$(json "$work/bp.json" "j['points'][len(j['points']) // 2]['index']")
"$bin" orbit "$row2" --parent "$work/bp.json" --from-point "$mid" --json "$work/from_bp.json" \
  > "$work/from_bp.out" 2>&1
check "orbit from a curve's point: exit 0, the point named" grep -qF "start saved $work/bp.json, point $mid (k = " "$work/from_bp.out"
check "... its period the point's (1e-9 relative), a multiplier at +1 (1e-7) beside the trivial" test "$(json "$work/from_bp.json" "(lambda p: abs(j['period'] - p['period']) < 1e-9 * p['period'] and sum(abs(complex(*m) - 1) < 1e-7 for m in j['multipliers']) >= 2)([q for q in json.load(open('$work/bp.json'))['points'] if q['index'] == $mid][0])")" = True
"$bin" orbit "$row2" --parent "$work/bp.json" --from-point PD1 > /dev/null 2> "$work/from_bp_bad.err"
check "... an event name refused: a curve's points by index" grep -qF "is a curve (curve --json); expected a point's index along it" "$work/from_bp_bad.err"

# A curve's period asked for (AUTO's UZ and UZSTOP on PERIOD), exact on the Bautin normal form
# r' = r (mu + 2 r^2 - r^4), theta' = w: its cycles' fold lies at mu = -1 (r = 1) for every w, and
# the fold's period is 2 pi / w, so the curve in (mu, w) reports period 5 at w = 2 pi / 5 and
# stops at period 4 at w = pi / 2 (to 1e-9 relative; measured 3e-12), mu = -1 (1e-9). 0.1 s.
cat > "$work/bautin.toml" <<'TOML'
kind = "equations"
name = "bautin"
[states]
x = 1.4142135623730951
y = 0.0
[parameters]
mu = 0.0
w = 1.0
[intermediates]
rr = "x*x + y*y"
g = "mu + 2*rr - rr*rr"
[equations]
x = "x*g - w*y"
y = "y*g + w*x"
TOML
"$bin" continue "$work/bautin.toml" --param mu --from 0 --to -2 --quiet --json "$work/bautin.json" > /dev/null
"$bin" curve "$work/bautin.toml" --parent "$work/bautin.json" --event LP1 --param mu --from -2 --to 0 \
  --second w --second-from 0.5 --second-to 2 --user-value period=5 --stop-at period=4 --quiet \
  --json "$work/bautin_fold.json" --csv "$work/bautin_fold.csv" > "$work/bautin_fold.out"
check "a curve's --user-value and --stop-at on the period: exit 0, stopped there" grep -qF "reached the value asked for: stop at period = 4" "$work/bautin_fold.out"
check "... UZ at w = 2 pi / 5 and pi / 2 (1e-9 relative), mu = -1 (1e-9)" test "$(json "$work/bautin_fold.json" "[e['type'] for e in j['events']] == ['UZ', 'UZ'] and all(e['located'] and abs(e['second'] - w) < 1e-9 * w and abs(e['first'] + 1) < 1e-9 for e, w in zip(j['events'], (2 * math.pi / 5, math.pi / 2)))")" = True
# Every orbit on the fold is the circle r = 1: each point's and event's largest and smallest x
# are +-1 (1e-9; AUTO's MAX U per point of a curve), in the JSON and the CSV.
check "... each point's max and min of x and y +-1 (1e-9), events' too" test "$(json "$work/bautin_fold.json" "all(abs(p[k][s] - (1 if k == 'max' else -1)) < 1e-9 for p in j['points'] + [e['point'] for e in j['events']] for k in ('max', 'min') for s in (0, 1))")" = True
check "... the CSV's max_x column" test "$(/usr/bin/python3 -c "
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(len(rows) > 5 and all(abs(float(r['max_x']) - 1) < 1e-9 and abs(float(r['min_y']) + 1) < 1e-9 for r in rows))" "$work/bautin_fold.csv")" = True
"$bin" curve "$work/bautin.toml" --parent "$work/bautin.json" --event LP1 --param mu --from -2 --to 0 \
  --second w --second-from 0.5 --second-to 2 --stop-at max_x=1 > /dev/null 2> "$work/bautin_bad.err"
check "... on another quantity: refused, saying what a curve takes" grep -qF -- "--stop-at max_x=1: a curve's points carry their period and parameters only; expected period=VALUE, mu=VALUE or w=VALUE" "$work/bautin_bad.err"

# The fast preset's BP curve at looser tolerances: the corrector's tolerances and difference
# step follow the integration's measured noise (CurveSystem::measure_noise). Before, the chord
# counted its stalled noise-level steps as divergence: no curve at rtol 5e-8, a spurious turn
# and an early end at 3e-8. Expected end: k = 47.0609656873 at c = 0.021 (BDF rtol 1e-12 on the
# whole state, 2026-11-27; the default preset gives 47.060965683); fast's stated accuracy is
# about 4e-7 relative (measured: 4e-9 at rtol 5e-8, 2.4e-8 at 1e-7).
for r in 5e-8 1e-7; do
  "$bin" curve "$row2" --start anti-phase --param k --from 46 --to 48 --event BP1 --second c \
    --second-from 0.0185 --second-to 0.021 --accuracy fast --rtol $r --quiet \
    --json "$work/fast$r.json" > "$work/fast$r.out" 2>&1
  check "fast BP curve at rtol $r exits 0" test $? -eq 0
  check "... reaches c = 0.021 at k within 1e-7 relative of 47.0609656873, with no turn" \
    test "$(json "$work/fast$r.json" "j['points'][-1]['second'] == 0.021 and abs(j['points'][-1]['first'] / 47.0609656873 - 1) < 1e-7 and not j['events']")" = True
done

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
check "a window outside the parameter's domain is refused" grep -q -- "--second-from: c = -0.1 is outside the model.s domain" "$work/bad.err"

# A small map: the anti-phase orbit near its BP, the BP curve in c and a 3 x 2 stability grid.
cat > "$work/map_small.toml" <<TOML
title = "small"
case = "$row2"
params = "table2"
marks = ["table2"]
[first]
parameter = "k"
from = 45.0
to = 49.0
points = 3
[second]
parameter = "c"
from = 0.0185
to = 0.03
points = 2
[[orbits]]
name = "anti-phase"
start = "anti-phase"
TOML
"$bin" map "$work/map_small.toml" --out "$work" --quiet > "$work/map.out" 2>&1
check "map exits 0" test $? -eq 0
check "map: one BP curve from the branch's BP, a CSV of it" test -s "$work/map_small-anti-phase-BP1.csv"
check "map JSON: the curve, the grid (unstable at k = 45 and 47, left of the BP curve at 47.07 and 47.04 N/m; stable at 49), the mark" \
  test "$(json "$work/map_small.json" "[c['kind'] for c in j['orbits'][0]['curves']] == ['BP'] and j['orbits'][0]['grid']['unstable_count'] == [[1, 1, 0], [1, 1, 0]] and j['marks'][0]['name'] == 'table2'")" = True
printf 'case = "%s"\n[first]\nparameter = "k"\nfrom = 1.0\nto = 2.0\n[second]\nparameter = "k"\nfrom = 0.0\nto = 1.0\n[[orbits]]\nname = "a"\nstart = "anti-phase"\n' "$row2" > "$work/bad_map.toml"
"$bin" map "$work/bad_map.toml" --out "$work" 2> "$work/bad.err"
check "a map with the same parameter twice exits 2" test $? -eq 2
check "... naming the file, the line and the key" grep -q "bad_map.toml:6: key 'second.parameter': expected a parameter other than first.parameter" "$work/bad.err"
printf 'case = "%s"\n[first]\nparameter = "k"\nfrom = 1.0\nto = 2.0\n[second]\nparameter = "c"\nfrom = 0.1\nto = 1.0\n[[orbits]]\nname = "a"\nstart = "anti-phase"\n' "$row2" > "$work/bad_map.toml"
"$bin" map "$work/bad_map.toml" --out "$work" 2> "$work/bad.err"
check "a map window without the start's value is refused" grep -q "does not contain c = 0.0185" "$work/bad.err"
printf 'case = "%s"\ncolour = 1\n' "$row2" > "$work/bad_map.toml"
"$bin" map "$work/bad_map.toml" --out "$work" 2> "$work/bad.err"
check "a map with an unknown key is refused" grep -q "bad_map.toml:2: key 'colour'" "$work/bad.err"

# A map of an equation case file (AUTO-07p's abc, compiled once): the cycle family's two folds
# in p1 at p3 = 1.55, each followed as an LP curve in (p1, p3); each curve passes through the
# fold it was seeded at (1e-9 in p1). The orbit needs no start: the file's [states].
cat > "$work/abc_map.toml" <<TOML
case = "$src/cases/examples/abc.toml"
[first]
parameter = "p1"
from = 0.21
to = 0.22
points = 0
[second]
parameter = "p3"
from = 1.54
to = 1.56
points = 0
[[orbits]]
name = "cycle"
at = 0.215
TOML
SYMPATHY_CACHE_DIR="$work/cache" "$bin" map "$work/abc_map.toml" --out "$work" --quiet > "$work/abc_map.out" 2>&1
check "map on an equation case file exits 0" test $? -eq 0
check "... two LP curves, each through the fold it starts at" test "$(/usr/bin/python3 -c "
import csv, json, sys
o = json.load(open(sys.argv[1]))['orbits'][0]
folds = [e['value'] for e in o['branch']['events'] if e['type'] == 'LP']
ok = len(folds) == 2 and [c['kind'] for c in o['curves']] == ['LP', 'LP']
for c in o['curves']:
    rows = list(csv.DictReader(open(sys.argv[2] + '/' + c['csv'])))
    ok = ok and any(abs(float(r['p3']) - 1.55) < 1e-12 and min(abs(float(r['p1']) - f) for f in folds) < 1e-9 for r in rows)
print(ok)" "$work/abc_map.json" "$work")" = True
# The same orbit from a saved run's point (map files' parent and from_point, AUTO's IRS): the
# branch JSON's point 0 at p1 = 0.215, continued on the map as the case's start is: the same
# two folds (1e-9).
SYMPATHY_CACHE_DIR="$work/cache" "$bin" continue "$src/cases/examples/abc.toml" --param p1 \
  --from 0.21 --to 0.22 --at 0.215 --quiet --json "$work/abc_saved.json" > /dev/null 2>&1
sed 's|^at = 0.215$|parent = "abc_saved.json"\nfrom_point = 0|' "$work/abc_map.toml" > "$work/abc_map_saved.toml"
SYMPATHY_CACHE_DIR="$work/cache" "$bin" map "$work/abc_map_saved.toml" --out "$work" --quiet > "$work/abc_map_saved.out" 2>&1
check "a map orbit from parent and from_point exits 0, its start the saved point" test "$(/usr/bin/python3 -c "
import json, sys
a = json.load(open(sys.argv[1]))['orbits'][0]
b = json.load(open(sys.argv[2]))['orbits'][0]
fa = sorted(e['value'] for e in a['branch']['events'] if e['type'] == 'LP')
fb = sorted(e['value'] for e in b['branch']['events'] if e['type'] == 'LP')
print(b['start'].startswith('saved ') and len(fb) == 2 and len(b['curves']) == 2 and
      all(abs(x - y) < 1e-9 for x, y in zip(fa, fb)))" "$work/abc_map.json" "$work/abc_map_saved.json")" = True
sed 's|^at = 0.215$|parent = "abc_saved.json"|' "$work/abc_map.toml" > "$work/abc_map_bad.toml"
"$bin" map "$work/abc_map_bad.toml" --out "$work" > /dev/null 2> "$work/bad.err"
check "... parent without from_point refused, naming the key" grep -q "key 'orbits\[1\].from_point' is missing" "$work/bad.err"
# A forced system has no curves: refused before any work.
sed "s|abc.toml|ffn.toml|; s|p1|a|g; s|p3|amp|; s|0.21|0.3|; s|0.22|0.5|; s|0.215|0.4|; s|1.54|0.05|; s|1.56|0.2|" \
  "$work/abc_map.toml" > "$work/ffn_map.toml"
SYMPATHY_CACHE_DIR="$work/cache" "$bin" map "$work/ffn_map.toml" --out "$work" > /dev/null 2> "$work/ffn_map.err"
check "map on a forced system exits 2" test $? -eq 2
check "... saying why" grep -qF "map (two-parameter curves) is for autonomous systems" "$work/ffn_map.err"
# Maps of equilibria ([[equilibria]]): the BT normal form's branch in b1 at b2 = -1 has an HB
# and an LP; their curves are the Hopf line b1 = 0 and the fold parabola b1 = b2^2 / 4 (every
# CSV row to 1e-9), each through the BT point at the origin (1e-8), and no third curve (the BT
# on each starts the other).
cat > "$work/bt_map.toml" <<TOML
case = "$src/cases/examples/bt.toml"
[first]
parameter = "b1"
from = -0.5
to = 0.5
points = 0
[second]
parameter = "b2"
from = -1.5
to = 1.0
points = 0
[[equilibria]]
name = "rest"
TOML
SYMPATHY_CACHE_DIR="$work/cache" "$bin" map "$work/bt_map.toml" --out "$work" --quiet > "$work/bt_map.out" 2>&1
check "a map of equilibria exits 0" test $? -eq 0
check "... its HB line and LP parabola on their closed forms, each with the BT at the origin" test "$(/usr/bin/python3 -c "
import csv, json, sys
e = json.load(open(sys.argv[1]))['equilibria'][0]
ok = sorted(c['kind'] for c in e['curves']) == ['HB', 'LP'] and e['branch']['kind'] == 'equilibria'
for c in e['curves']:
    rows = list(csv.DictReader(open(sys.argv[2] + '/' + c['csv'])))
    exact = (lambda b2: b2 * b2 / 4) if c['kind'] == 'LP' else (lambda b2: 0.0)
    ok = ok and len(rows) > 20 and all(abs(float(r['b1']) - exact(float(r['b2']))) < 1e-9 for r in rows)
    bt = [x for x in c['events'] if x['type'] == 'BT']
    ok = ok and len(bt) == 1 and abs(bt[0]['first']) < 1e-8 and abs(bt[0]['second']) < 1e-8
print(ok)" "$work/bt_map.json" "$work")" = True
check "... printed as a table per entry" grep -q "^rest (equilibria): " "$work/bt_map.out"
# Two Hopf pairs (double_hopf.toml): the first pair's Hopf line b1 = 0 and, from its double Hopf
# point, the second pair's line b2 = 0 (omega sqrt 2), every row to 1e-9.
sed "s|bt.toml|double_hopf.toml|; s|^from = -1.5|from = -0.6|" "$work/bt_map.toml" > "$work/dh_map.toml"
SYMPATHY_CACHE_DIR="$work/cache" "$bin" map "$work/dh_map.toml" --out "$work" --quiet > "$work/dh_map.out" 2>&1
check "the double Hopf map: the other pair's Hopf curve from the HH point" test "$(/usr/bin/python3 -c "
import csv, json, math, sys
cs = json.load(open(sys.argv[1]))['equilibria'][0]['curves']
ok = len(cs) == 2 and cs[1]['origin'].startswith('HH at')
for c, fixed, omega in ((cs[0], 'b1', 1.0), (cs[1], 'b2', math.sqrt(2))):
    rows = list(csv.DictReader(open(sys.argv[2] + '/' + c['csv'])))
    ok = ok and len(rows) > 10 and all(abs(float(r[fixed])) < 1e-9 and abs(float(r['omega']) - omega) < 1e-9 for r in rows)
print(ok)" "$work/dh_map.json" "$work")" = True
# Bad [[equilibria]] entries, refused before any work, naming the line and the key.
sed -n '1,/^name = "rest"$/p' "$work/bt_map.toml" > "$work/bad_map.toml"
printf 'step = 0.1\n' >> "$work/bad_map.toml"
"$bin" map "$work/bad_map.toml" --out "$work" 2> "$work/bad.err"
check "an unknown key of an equilibria entry is refused" grep -q "bad_map.toml:14: key 'equilibria\[1\].step'" "$work/bad.err"
printf '[[orbits]]\nname = "rest"\n' >> "$work/bt_map.toml"
"$bin" map "$work/bt_map.toml" --out "$work" 2> "$work/bad.err"
check "a name an orbit and an equilibria entry share is refused" grep -q "key 'equilibria\[1\].name': expected a name no other orbit or equilibria entry has" "$work/bad.err"
printf 'case = "%s"\n[first]\nparameter = "k"\nfrom = 1.0\nto = 100.0\n[second]\nparameter = "c"\nfrom = 0.0\nto = 0.5\n' "$row2" > "$work/bad_map.toml"
"$bin" map "$work/bad_map.toml" --out "$work" 2> "$work/bad.err"
check "a map with neither orbits nor equilibria is refused" grep -q "key 'orbits' is missing; expected \[\[orbits\]\] tables, \[\[equilibria\]\] tables or both" "$work/bad.err"
printf '[[equilibria]]\nname = "rest"\n' >> "$work/bad_map.toml"
"$bin" map "$work/bad_map.toml" --out "$work" 2> "$work/bad.err"
check "a metronome case's equilibria entry without a start is refused" grep -q "equilibria 'rest': key 'start' is missing" "$work/bad.err"
exit "$failures"
