#!/usr/bin/env bash
# The continue and study commands end to end: JSON and CSV contents, Ctrl-C, bad input.
# Usage: continue_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
json() { /usr/bin/python3 -c "import json,math,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }

# The anti-phase branch across its first stability change (paper: about 47 N/m).
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param k --from 40 --to 52 \
  --csv "$work/anti.csv" --json "$work/anti.json" > "$work/anti.out" 2> "$work/anti.err"
check "continue exits 0" test $? -eq 0
check "table of bifurcation points printed" grep -q '^  BP   47.06' "$work/anti.out"
check "run time printed" grep -q 'run time' "$work/anti.out"
check "progress lines on stderr" grep -q '^  \[   1\] k = ' "$work/anti.err"
for key in parameter points events seconds; do
  check "JSON has '$key'" test "$(json "$work/anti.json" "'$key' in j")" = True
done
check "JSON points carry value, period, stable, multipliers, trivial_multiplier_error" \
  test "$(json "$work/anti.json" "all(all(k in p for k in ('value','period','stable','multipliers','trivial_multiplier_error')) for p in j['points'])")" = True
check "JSON events: BP then NS with type, value, period, multipliers" \
  test "$(json "$work/anti.json" "[e['type'] for e in j['events']] == ['BP', 'NS'] and all(all(k in e for k in ('type','value','period','multipliers')) for e in j['events'])")" = True
check "every point within 1e-8 of a trivial multiplier of 1" \
  test "$(json "$work/anti.json" "max(p['trivial_multiplier_error'] for p in j['points']) < 1e-8")" = True
check "CSV has a row per point" test "$(($(wc -l < "$work/anti.csv") - 1))" -eq "$(json "$work/anti.json" "len(j['points'])")"
check "CSV header" grep -q '^index,k,period,frequency,stability' "$work/anti.csv"
check "JSON: the start's stiffness as the run time line printed it" \
  test "$(json "$work/anti.json" "'%.2g' % j['stiffness']['indicator']")" = "$(grep -o 'stiffness indicator [0-9.]*' "$work/anti.out" | awk '{print $3}')"
check "the last point lies on the bound, k = 52 exactly" \
  test "$(json "$work/anti.json" "j['points'][-1]['value'] == 52.0 and max(p['value'] for p in j['points']) <= 52.0")" = True

# Segments side by side (--threads): the same branch, to the bit, on one thread and on two.
for t in 1 2; do
  "$bin" continue "$src/cases/row2.toml" --start in-phase --param k --from 14 --to 16 --segments 2 \
    --threads $t --max-points 4 --quiet --csv "$work/seg$t.csv" > /dev/null 2>&1
  check "--segments 2 --threads $t exits 0" test $? -eq 0
done
check "the same branch on one thread and on two" cmp -s "$work/seg1.csv" "$work/seg2.csv"

# Ctrl-C: the run stops after the point in progress, keeping the CSV and writing the JSON.
# (Stale files from an earlier run would send the signal before the handler is in place.)
rm -f "$work/int.csv" "$work/int.json"
"$bin" continue "$src/cases/row2.toml" --start in-phase --param k --from 1 --to 100 \
  --csv "$work/int.csv" --json "$work/int.json" > "$work/int.out" 2>&1 &
pid=$!
wait_for_lines "$work/int.csv" 4
kill -INT $pid
wait $pid
check "interrupted run exits 6 (documented: interrupted, outputs complete)" test $? -eq 6
check "interrupted run says so" grep -q 'stopped: interrupted' "$work/int.out"
check "interrupted run keeps its points" test "$(json "$work/int.json" "len(j['points']) >= 3")" = True

# Bad input.
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param q --from 1 --to 2 2> "$work/bad.err"
check "unknown parameter exits 2" test $? -eq 2
check "unknown parameter is named" grep -q -- "--param q: not a parameter" "$work/bad.err"
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param k --from 5 --to 5 2> "$work/bad.err"
check "--from = --to exits 2" test $? -eq 2
printf 'case = "../row2.toml"\nparameter = "k"\ncolour = 3\n' > "$work/bad.toml"
"$bin" study "$work/bad.toml" --out "$work" 2> "$work/bad.err"
check "study with an unknown key exits 2" test $? -eq 2
check "study error names file, line and key" grep -q "bad.toml:3: key 'colour'" "$work/bad.err"
printf 'case = "%s"\nparameter = "k"\n[[branches]]\nname = "a"\nstart = "anti-phase"\nfrom = 1.0\nto = 2.0\nmax_points = 2.5\n' "$src/cases/row2.toml" > "$work/bad.toml"
"$bin" study "$work/bad.toml" --out "$work" 2> "$work/bad.err"
check "study refuses a fractional max_points, saying what it got" \
  grep -q "bad.toml:8: key 'branches\[1\].max_points': expected an integer, got 2.5" "$work/bad.err"
printf 'case = "%s"\nparameter = "k"\n[[branches]]\nname = "a"\nstart = "anti-phase"\nfrom = 1.0\nto = 2.0\nmax_points = 4294967297\n' "$src/cases/row2.toml" > "$work/bad.toml"
"$bin" study "$work/bad.toml" --out "$work" 2> "$work/bad.err"
check "study refuses a max_points beyond int, not narrowed to 1" \
  grep -q "bad.toml:8: key 'branches\[1\].max_points': expected an integer between -2147483648 and 2147483647, got 4294967297" "$work/bad.err"

# Branch switching at the anti-phase branch point (k = 47.0656): the born branch runs to lower
# k, off the subspace x = 0, th2 = -th1 (the platform moves, the pendula swing unequally).
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param k --from 45 --to 49 \
  --switch-at BP1 --json "$work/born.json" --quiet > "$work/born.out" 2>&1
check "switch exits 0" test $? -eq 0
check "the born branch names its origin" grep -q "born at the parent branch's BP at k = 47.06" "$work/born.out"
check "JSON origin is the BP" test "$(json "$work/born.json" "j['origin'].startswith('BP at k = 47.0655')")" = True
check "born orbits lie at k <= the BP, the platform moving, amplitudes unequal" \
  test "$(json "$work/born.json" "all(p['value'] <= 47.06557 for p in j['points']) and all(p['amplitudes'][0] > 1e-4 and abs(p['amplitudes'][1] - p['amplitudes'][2]) > 1e-3 for p in j['points'] if p['value'] < 47.0)")" = True
# ... and from a saved parent: the JSON of the branch, its events carrying what switching needs.
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param k --from 45 --to 49 \
  --json "$work/parent.json" --quiet > /dev/null 2>&1
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param k --from 45 --to 49 \
  --switch-at BP1 --parent "$work/parent.json" --json "$work/born2.json" --quiet > /dev/null 2>&1
check "switch from a saved parent exits 0" test $? -eq 0
check "the born branch from a saved parent is the same branch" \
  test "$(json "$work/born2.json" "j['origin'].startswith('BP at k = 47.0655') and min(p['value'] for p in j['points']) == 45.0")" = True
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param k --from 45 --to 49 \
  --switch-at BP1 --parent "$work/parent.json" --json "$work/parent.json" --quiet 2> "$work/bad.err"
check "the output cannot replace the parent" grep -q "is the --parent" "$work/bad.err"
printf '{"parameter": "k"}' > "$work/half.json"
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param k --from 45 --to 49 \
  --switch-at BP1 --parent "$work/half.json" --quiet 2> "$work/bad.err"
check "a parent JSON without its values exits 2 naming the key" grep -q "half.json: key 'parameter_values' is missing" "$work/bad.err"
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param k --from 45 --to 49 \
  --switch-at NS1 2> "$work/bad.err"
check "switching at an NS exits 2 before any work" test $? -eq 2
check "switching at an NS says where a branch is born" grep -q "BP, PD or HB followed by its number" "$work/bad.err"
"$bin" continue "$src/cases/row2.toml" --start anti-phase --param k --from 45 --to 49 \
  --switch-at PD1 --quiet 2> "$work/bad.err"
check "switching at a missing event exits 2" test $? -eq 2
check "a missing event is named with the branch's events" grep -q "PD1: the branch has no such event; it has BP1 at 47.06" "$work/bad.err"

# Chained study branches: switch_at = "NAME:EVENT" names a branch listed before, not switched.
printf 'case = "%s"\nparameter = "k"\n[[branches]]\nname = "a"\nstart = "anti-phase"\nfrom = 41.0\nto = 48.0\n[[branches]]\nname = "b"\nfrom = 41.0\nto = 48.0\nswitch_at = "z:BP1"\n' "$src/cases/row2.toml" > "$work/bad.toml"
"$bin" study "$work/bad.toml" --out "$work" 2> "$work/bad.err"
check "a chained branch naming no earlier branch is refused, file, line and key named" \
  grep -q "bad.toml:12: key 'branches\[2\].switch_at': expected an event of this branch (BP1) or of a branch listed before it (NAME:BP1); 'z' is not one" "$work/bad.err"
printf 'case = "%s"\nparameter = "k"\n[[branches]]\nname = "a"\nstart = "anti-phase"\nfrom = 41.0\nto = 48.0\nswitch_at = "BP1"\n[[branches]]\nname = "b"\nfrom = 41.0\nto = 48.0\nswitch_at = "a:BP1"\n' "$src/cases/row2.toml" > "$work/bad.toml"
"$bin" study "$work/bad.toml" --out "$work" 2> "$work/bad.err"
check "a chain of two switches is refused" grep -q "expected a branch that is not itself switched ('a' is)" "$work/bad.err"
# Shooting segments both ways (AUTO re-meshes both ways): AUTO's ab at p2 = 16, the family born
# at HB1, passes a spike where one segment fails (refined to 2, then 4) and comes back to orbits
# one segment resolves, where it returns to 1 (Continuation::Run::accept: three points in a row
# whose growth on half the segments stays below 100). Its user point at p1 = 0.25, computed on 1
# segment, is the branch's on 4 throughout (--segments 4: never below what is asked) to 1e-9 in
# the period (measured 3.4e-12); every point on 1 segment after the spike is resolved (trivial
# multiplier within 1e-8; measured below 1e-9). About 5 s with the compile.
ab=$src/tests/auto/cases/ab.toml
"$bin" equilibria "$ab" --set p2=16 --param p1 --from 0 --to 0.25 --quiet --json "$work/ab_eq.json" > /dev/null
for s in 1 4; do
  "$bin" continue "$ab" --set p2=16 --param p1 --from 0.1 --to 0.25 --switch-at HB1 \
    --parent "$work/ab_eq.json" --user-points 0.25 --segments $s --quiet --json "$work/ab$s.json" > /dev/null
  check "ab's HB1 family on --segments $s exits 0" test $? -eq 0
done
check "ab: refined to 4 segments, then back to 1" \
  test "$(json "$work/ab1.json" "(lambda s: 4 in s and s[-1] == 1 and s.index(4) < len(s) - 1 - s[::-1].index(4))([p['segments'] for p in sorted(j['points'], key=lambda p: p['index'])])")" = True
check "ab: on --segments 4 never fewer" test "$(json "$work/ab4.json" "min(p['segments'] for p in j['points'])")" -eq 4
check "ab: the points on 1 segment after the spike resolved (trivial multiplier within 1e-8)" \
  test "$(json "$work/ab1.json" "(lambda ps: max(p['trivial_multiplier_error'] for p in ps[max(i for i, p in enumerate(ps) if p['segments'] == 4):] if p['segments'] == 1) < 1e-8)(sorted(j['points'], key=lambda p: p['index']))")" = True
uz() { json "$1" "[e['period'] for e in j['events'] if e['type'] == 'UZ' and e['trusted']][0]"; }
check "ab: the user point at p1 = 0.25 on 1 segment is the one on 4 (period to 1e-9)" \
  /usr/bin/python3 -c "import sys; sys.exit(abs($(uz "$work/ab1.json") - $(uz "$work/ab4.json")) > 1e-9)"

# A restart from a saved orbit (--parent FILE --from-point POINT, AUTO's IRS), exact on lcbp: the
# circles r = p1 (period 1) cross the circles r = p2 at the branch point p1 = p2 = 2; the branch
# born there is r = p1, unstable for p1 < p2 (radial multiplier exp(-p1 (p1 - p2))). Its user
# point at p1 = 1.5 (UZ1), an unstable orbit, restarted in the other parameter p2 from 2 to 2.5:
# every point the circle r = 1.5 to 1e-9, period 1, its largest multiplier exp(0.75) at p2 = 2
# and exp(1.5) at 2.5 (to 1e-7); its first point the saved one (state to 1e-9). From a point's
# index, orbit gives back the saved orbit. Under 1 s.
lcbp=$src/cases/examples/lcbp.toml
"$bin" continue "$lcbp" --param p1 --from 1 --to 3 --quiet --json "$work/lcbp_a.json" > /dev/null
"$bin" continue "$lcbp" --param p1 --from 1 --to 3 --switch-at BP1 --parent "$work/lcbp_a.json" \
  --user-points 1.5 --quiet --json "$work/lcbp_b.json" > /dev/null
check "the switched branch's events described too: UZ1's max and min of x and y are +-1.5 (to 1e-7)" test "$(json "$work/lcbp_b.json" "(lambda e: all(abs(v - 1.5) < 1e-7 for v in e['max']) and all(abs(v + 1.5) < 1e-7 for v in e['min']))([e for e in j['events'] if e['type'] == 'UZ'][0])")" = True
"$bin" continue "$lcbp" --parent "$work/lcbp_b.json" --from-point UZ1 --param p2 --from 2 --to 2.5 \
  --quiet --json "$work/lcbp_c.json" > "$work/lcbp_c.out"
check "restart from a saved user point in another parameter exits 0" test $? -eq 0
check "... its start named" grep -qF "start saved $work/lcbp_b.json, UZ1 (p1 = 1.5)" "$work/lcbp_c.out"
check "... every point the circle r = 1.5, period 1 (to 1e-9)" test "$(json "$work/lcbp_c.json" "all(abs(math.hypot(*p['state0']) - 1.5) < 1e-9 and abs(p['period'] - 1) < 1e-9 for p in j['points'])")" = True
check "... unstable: largest multiplier exp(-p1 (p1 - p2)) at both ends (to 1e-7)" test "$(json "$work/lcbp_c.json" "(lambda ps: abs(max(abs(complex(*m)) for m in ps[0]['multipliers']) - math.exp(0.75)) < 1e-7 and abs(max(abs(complex(*m)) for m in ps[-1]['multipliers']) - math.exp(1.5)) < 1e-7 and not ps[0]['stable'])(sorted(j['points'], key=lambda p: p['index']))")" = True
check "... its first point the saved orbit (to 1e-9)" /usr/bin/python3 -c "
import json, sys
b = json.load(open(sys.argv[1])); c = json.load(open(sys.argv[2]))
uz = [e for e in b['events'] if e['type'] == 'UZ'][0]['state0']
first = [p for p in c['points'] if p['index'] == 0][0]['state0']
sys.exit(max(abs(u - v) for u, v in zip(uz, first)) > 1e-9)" "$work/lcbp_b.json" "$work/lcbp_c.json"
"$bin" orbit "$lcbp" --parent "$work/lcbp_b.json" --from-point 5 --json "$work/lcbp_o.json" > /dev/null
check "orbit from a saved point's index: the saved orbit (state and period to 1e-9)" /usr/bin/python3 -c "
import json, sys
b = json.load(open(sys.argv[1])); o = json.load(open(sys.argv[2]))
p = [q for q in b['points'] if q['index'] == 5][0]
sys.exit(abs(p['period'] - o['period']) > 1e-9 or max(abs(u - v) for u, v in zip(p['state0'], o['state0'])) > 1e-9)" "$work/lcbp_b.json" "$work/lcbp_o.json"
restart_bad() {  # restart_bad NAME EXPECTED ARGS...: refused with exit code 2, saying EXPECTED
  local name=$1 expected=$2; shift 2
  "$bin" continue "$lcbp" --param p2 --from 2 --to 2.5 "$@" > /dev/null 2> "$work/$name.err"
  check "$name: exit code 2" test $? -eq 2
  check "$name: says '$expected'" grep -qF -- "$expected" "$work/$name.err"
}
restart_bad no_parent "--from-point UZ1: expected --parent FILE too" --from-point UZ1
restart_bad with_start "--initial: not with --from-point UZ1" --parent "$work/lcbp_b.json" --from-point UZ1 --initial x=1
restart_bad no_point "$work/lcbp_b.json has no point 999; expected an index from" --parent "$work/lcbp_b.json" --from-point 999
restart_bad no_event "--from-point PD1: the branch has no such event; it has UZ1" --parent "$work/lcbp_b.json" --from-point PD1
restart_bad bad_name "--from-point XY1: expected a point's index" --parent "$work/lcbp_b.json" --from-point XY1

# User values and stops on a quantity of the orbits (AUTO's UZ and UZSTOP on any quantity), exact
# on the Hopf normal form (cases/examples/hopf.toml: the circle of radius sqrt(mu), period 2 pi /
# w): in mu, max_x = 0.6 at mu = 0.36 and the stop at max_x = 0.8 at mu = 0.64 (located on the
# one locator: to 1e-9 relative; measured 3e-11), no point kept beyond it; in w, period = 4 at
# w = pi / 2 and the stop at period = 3 at w = 2 pi / 3 (the period held at the value: to 1e-9
# relative; measured 1e-12, the period exact).
hopf=$src/cases/examples/hopf.toml
"$bin" continue "$hopf" --param mu --from 0.25 --to 1 --user-value max_x=0.6 --stop-at max_x=0.8 \
  --quiet --json "$work/uv_mu.json" > "$work/uv_mu.out"
check "--user-value and --stop-at on max_x exit 0" test $? -eq 0
check "... stopped there, saying so" grep -qF "stopped: reached the value asked for: stop at max_x = 0.8" "$work/uv_mu.out"
check "... UZ at mu = 0.36 and 0.64 (max x = sqrt(mu)), trusted, to 1e-9 relative" test "$(json "$work/uv_mu.json" "[e['type'] for e in j['events']] == ['UZ', 'UZ'] and all(e['trusted'] and abs(e['value'] - v) < 1e-9 * v for e, v in zip(j['events'], (0.36, 0.64)))")" = True
check "... no point beyond the stop" test "$(json "$work/uv_mu.json" "max(p['value'] for p in j['points']) < 0.64")" = True
"$bin" continue "$hopf" --param w --from 1 --to 3 --user-value period=4 --stop-at period=3 \
  --quiet --json "$work/uv_w.json" > /dev/null
check "... on the period: UZ at w = pi / 2 and 2 pi / 3 to 1e-9 relative, the period exact" test "$(json "$work/uv_w.json" "[e['type'] for e in j['events']] == ['UZ', 'UZ'] and all(abs(e['value'] - w) < 1e-9 * w and e['period'] == T for e, w, T in zip(j['events'], (math.pi / 2, 2 * math.pi / 3), (4, 3)))")" = True
"$bin" continue "$hopf" --param w --from 1 --to 3 --user-value peri=4 > /dev/null 2> "$work/uv_bad.err"
check "an unknown quantity: exit code 2" test $? -eq 2
check "... naming the quantities there are" grep -qF -- "--user-value peri=4: not a quantity of the orbits; expected one of: period, max_x, max_y, min_x, min_y, x, y" "$work/uv_bad.err"

# A state's value at the orbit's section point (state0): on the Hopf normal form started on the
# x axis (Newton at once from (0.5, 0)) the section stays the plane y = 0, where x = sqrt(mu); the
# stop at x = 0.8 is at mu = 0.64 (to 1e-9 relative; measured 1e-12).
"$bin" continue "$hopf" --param mu --from 0.25 --to 1 --initial x=0.5 --initial y=0 \
  --period-guess 6.283 --stop-at x=0.8 --quiet --json "$work/uv_x.json" > /dev/null
check "... on a state at the section: stop at x = 0.8 at mu = 0.64 (1e-9 relative)" test "$(json "$work/uv_x.json" "[e['type'] for e in j['events']] == ['UZ'] and abs(j['events'][0]['value'] - 0.64) < 1e-9 * 0.64 and abs(j['events'][0]['state0'][0] - 0.8) < 1e-9")" = True

# A stop at a longer period goes on past the homoclinic approach that otherwise ends a branch:
# AUTO's pen to T = 30 (its script's UZSTOP) ended at T 23.0 by the approach, then at T 27.1
# where its multipliers were no longer resolved; it now reaches T = 30 (ri = 0.127009, AUTO's
# printed value, within half its last digit: the demo suite holds it), seeks no bifurcation past
# the approach (its multipliers' noise there gave a PD, a BP and an NS each few points) and says
# so (about 1 s).
"$bin" continue "$src/tests/auto/cases/pen.toml" --param ri --from 0.4 --to 0 --stop-at period=30 \
  --quiet --json "$work/pen_30.json" > "$work/pen_30.out"
check "a stop at period 30 goes on past the homoclinic approach to its UZ at T = 30" test "$(json "$work/pen_30.json" "j['stop'] == 'user value' and [e['type'] for e in j['events']] == ['PD', 'UZ'] and j['events'][1]['period'] == 30 and abs(j['events'][1]['value'] - 0.127009) < 1.27e-6")" = True
check "... and says from where no bifurcation was sought" grep -qF "past its homoclinic approach (from T = 22.9" "$work/pen_30.out"

# A study branch of an equation case file may leave out its start (the file's [states], as the
# studies guide says); a metronome case file's branch must name one, and the error lists them.
root=$(cd "$src" && pwd)
cat > "$work/nostart_eq.toml" << TOML
case = "$root/cases/examples/hopf.toml"
parameter = "mu"
[[branches]]
name = "cycles"
from = 0.25
to = 1
TOML
"$bin" study "$work/nostart_eq.toml" --out "$work/nostart_eq" > /dev/null 2>&1
check "a study branch of an equation case file without start: exit 0" test $? -eq 0
sed -e "s|examples/hopf.toml|row2.toml|" -e 's|"mu"|"k"|' -e 's|0.25|40|' -e 's|^to = 1|to = 45|' "$work/nostart_eq.toml" > "$work/nostart_met.toml"
"$bin" study "$work/nostart_met.toml" --out "$work/nostart_met" > /dev/null 2> "$work/nostart_met.err"
check "... of a metronome case file: exit 2, naming the starts" grep -qF "branch 'cycles': key 'start' is missing; expected the name of one of $root/cases/row2.toml's starts: in-phase, anti-phase" "$work/nostart_met.err"

# A study branch's user_value and stop_at tables, as continue's options: the same events on the
# Hopf normal form (mu = 0.36 and 0.64 to 1e-9 relative), an unknown quantity refused by key.
{ cat "$work/nostart_eq.toml"; printf 'user_value = { max_x = 0.6 }\nstop_at = { max_x = 0.8 }\n'; } > "$work/uv_study.toml"
"$bin" study "$work/uv_study.toml" --out "$work/uv_study" > /dev/null 2>&1
check "a study with user_value and stop_at: UZ at mu = 0.36 and 0.64 (to 1e-9 relative)" test "$(json "$work/uv_study/uv_study.json" "(lambda es: len(es) == 2 and all(abs(e['value'] - v) < 1e-9 * v for e, v in zip(es, (0.36, 0.64))))(j['branches'][0]['events'])")" = True
sed -i 's/max_x = 0.6/peri = 4/' "$work/uv_study.toml"
"$bin" study "$work/uv_study.toml" --out "$work/uv_study" > /dev/null 2> "$work/uv_study.err"
check "... an unknown quantity refused, file, line and key named" grep -qF "uv_study.toml:7: key 'branches.cycles.user_value' peri=4: not a quantity of the orbits" "$work/uv_study.err"

# A study branch from a saved point (parent and from_point, as continue's --parent --from-point;
# the file relative to the study file): lcbp's user point restarted in p2, the same circle r = 1.5
# as the command line's run (every point to 1e-9); beside start, refused by key.
cp "$work/lcbp_b.json" "$work/saved_uz.json"
cat > "$work/from_saved.toml" << TOML
title = "from a saved point"
case = "$lcbp"
parameter = "p2"
[[branches]]
name = "restarted"
parent = "saved_uz.json"
from_point = "UZ1"
from = 2.0
to = 2.5
TOML
"$bin" study "$work/from_saved.toml" --out "$work/from_saved" > /dev/null 2>&1
check "a study branch from a saved point: exit 0, the circle r = 1.5 (1e-9)" test "$(json "$work/from_saved/from_saved.json" "(lambda b: len(b['points']) > 2 and all(abs(math.hypot(*p['state0']) - 1.5) < 1e-9 for p in b['points']))(j['branches'][0])")" = True
printf 'start = "x"\n' >> "$work/from_saved.toml"
"$bin" study "$work/from_saved.toml" --out "$work/from_saved" > /dev/null 2> "$work/from_saved.err"
check "... beside start: refused, key named" grep -qF "key 'branches[1].from_point': expected no start beside it" "$work/from_saved.err"

# A study branch born at a Hopf point of saved equilibria (switch_at = "HB1" with equilibria, the
# file relative to the study file): abc's family with AUTO's two folds of cycles (six digits), as
# continue --switch-at HB1 --parent finds them; equilibria beside another switch refused by key.
abc=$src/cases/examples/abc.toml
"$bin" equilibria "$abc" --param p1 --from 0 --to 0.4 --quiet --json "$work/abc_eq.json" > /dev/null
cat > "$work/hopf_study.toml" << TOML
title = "born at a Hopf point"
case = "$abc"
parameter = "p1"
[[branches]]
name = "hb1"
switch_at = "HB1"
equilibria = "abc_eq.json"
from = 0.2
to = 0.25
TOML
"$bin" study "$work/hopf_study.toml" --out "$work/hopf_study" > /dev/null 2>&1
check "a study branch from switch_at HB1 of saved equilibria: AUTO's folds 0.211903, 0.213697" test "$(json "$work/hopf_study/hopf_study.json" "sorted(round(e['value'], 6) for e in j['branches'][0]['events'] if e['type'] == 'LP') == [0.211903, 0.213697]")" = True
sed -i 's/switch_at = "HB1"/switch_at = "BP1"/' "$work/hopf_study.toml"
"$bin" study "$work/hopf_study.toml" --out "$work/hopf_study" > /dev/null 2> "$work/hopf_study.err"
check "... equilibria beside a BP switch refused, key named" grep -qF "key 'branches[1].equilibria': expected only with switch_at" "$work/hopf_study.err"

exit $failures
