#!/usr/bin/env bash
# Orbits started from data (--start-data: one recorded period, AUTO's `dat` files), user points
# (--user-points: AUTO's UZ) and states declared as angles, end to end on equation and metronome
# case files, with exact answers; bad data files refused with located errors before any work.
# Usage: data_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
export SYMPATHY_CACHE_DIR="$work/cache"  # never the user's cache
json_value() {
  /usr/bin/python3 -c "import json,math,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"
}
lcbp=$src/cases/examples/lcbp.toml hopf=$src/cases/examples/hopf.toml

# lcbp's circle r = p1 = 1 (cases/examples/lcbp.toml) is unstable (radial multiplier
# exp(-p1 (p1 - p2)) = e at p2 = 2), so no transient finds it; one period of it simulated from
# (1, 0) (the error grows by e per period: it stays on the circle to about 1e-8) starts Newton on
# it. Exact: period 1, the orbit through (1, 0) itself (the phase condition keeps the first row's
# section), multiplier e; to 1e-9.
"$bin" simulate "$lcbp" --initial x=1 --initial y=0 --t-end 1 --dt 0.01 --out "$work/r1.csv" 2> /dev/null
check "simulate writes one period" test "$(wc -l < "$work/r1.csv")" -eq 102
"$bin" orbit "$lcbp" --start-data "$work/r1.csv" --json "$work/r1.json" > "$work/r1.out"
check "orbit --start-data exits 0" test $? -eq 0
check "the report names the data and the period guess" grep -q "start data $work/r1.csv (101 rows over 1 s; period guess" "$work/r1.out"
check "the unstable circle r = 1: period 1" test "$(json_value "$work/r1.json" "abs(j['period'] - 1) < 1e-9")" = True
check "... through the first row (1, 0)" test "$(json_value "$work/r1.json" "max(abs(j['state0'][0] - 1), abs(j['state0'][1])) < 1e-9")" = True
check "... multiplier e" test "$(json_value "$work/r1.json" "min(abs(complex(*m) - math.e) for m in j['multipliers']) < 1e-8")" = True
check "... unstable" test "$(json_value "$work/r1.json" "j['stable']")" = False

# A metronome case: the in-phase orbit of row2, its period recorded by simulate from the orbit's
# own state (as given, to the last bit), 1.5 periods long (the guess is then the first return):
# read back, Newton in the whole state lands on the same orbit: period to 1e-9, state to 1e-8 (two
# solutions within Newton's 1e-9 of the residual; along the multiplier 0.988 a residual moves the
# state by up to 1 / (1 - 0.988) = 80 times itself: measured below 1e-9 from the 60 s transient's
# phase, 2e-9 from the early start's, OrbitOptions::early_newton_below).
"$bin" orbit "$src/cases/row2.toml" --start in-phase --json "$work/in.json" > /dev/null
initial=$(json_value "$work/in.json" "' '.join('--initial %s=%r' % (n, v) for n, v in zip(j['state_names'], j['state0']))")
t_end=$(json_value "$work/in.json" "1.5 * j['period']")
# shellcheck disable=SC2086
"$bin" simulate "$src/cases/row2.toml" $initial --t-end "$t_end" --dt 0.002 --out "$work/in.csv" 2> /dev/null
"$bin" orbit "$src/cases/row2.toml" --start-data "$work/in.csv" --json "$work/in_data.json" > "$work/in_data.out"
check "metronome: orbit --start-data exits 0" test $? -eq 0
check "metronome: the guess is the first return" grep -q "its first return, line" "$work/in_data.out"
check "metronome: the same period to 1e-9" test "$(json_value "$work/in_data.json" "abs(j['period'] - $(json_value "$work/in.json" "j['period']")) < 1e-9")" = True
check "metronome: the same state to 1e-8" /usr/bin/python3 -c "
import json,sys
a=json.load(open(sys.argv[1]))['state0']; b=json.load(open(sys.argv[2]))['state0']
sys.exit(0 if max(abs(x-y) for x,y in zip(a,b)) < 1e-8 else 1)" "$work/in.json" "$work/in_data.json"

# A study file's start_data and user_points keys: the in-phase branch of row2 from the recorded
# period and from the named start (in its symmetric subspace) give the same orbit at k = 15.
cat > "$work/study.toml" <<TOML
title = "from data"
case = "$(cd "$src" && pwd)/cases/row2.toml"
parameter = "k"
[[branches]]
name = "data"
start_data = "in.csv"       # relative to this file
from = 14.0
to = 16.0
user_points = [15.0]
[[branches]]
name = "named"
start = "in-phase"
from = 14.0
to = 16.0
user_points = [15.0]
TOML
"$bin" study "$work/study.toml" --out "$work/study" > "$work/study.out"
check "study with start_data and user_points exits 0" test $? -eq 0
check "study: one UZ at k = 15 on each branch, the same period to 1e-9" test "$(json_value "$work/study/study.json" "[[e['type'] for e in b['events']] for b in j['branches']] == [['UZ'], ['UZ']] and abs(j['branches'][0]['events'][0]['period'] - j['branches'][1]['events'][0]['period']) < 1e-9")" = True
sed -i 's/user_points = \[15.0\]/user_points = [15.0, 17.0]/' "$work/study.toml"
"$bin" study "$work/study.toml" --out "$work/study" > /dev/null 2> "$work/study.err"
check "study: a user point beyond from .. to is located" grep -qF "study.toml:9: key 'branches[1].user_points': expected values between from and to (the branch never reaches 17)" "$work/study.err"

# A curve from data, on a rotating orbit (AUTO's pen: ph1, ph2 angles gaining 2 pi a period):
# one period of the rotation at ri = 0.4 recorded, `curve --start-data` follows the PD curve of
# the ri-branch in eps as `curve` from the file's [states] does (the same points to the printed
# digits), and the curve's end on the window's edge ri = 0.4 is a PD of the one-parameter branch
# at that eps: independent, located there to its uncertainty (2e-9; measured 5e-12).
pen=$src/tests/auto/cases/pen.toml
"$bin" orbit "$pen" --json "$work/pen.json" > /dev/null
initial=$(json_value "$work/pen.json" "' '.join('--initial %s=%r' % (n, v) for n, v in zip(j['state_names'], j['state0']))")
# shellcheck disable=SC2086
"$bin" simulate "$pen" $initial --t-end "$(json_value "$work/pen.json" "j['period']")" --dt 0.01 --out "$work/pen.csv" 2> /dev/null
curve_args=(--param ri --from 0.4 --to 0.15 --event PD1 --second eps --second-from 0.05 --second-to 0.5 --quiet)
"$bin" curve "$pen" --start-data "$work/pen.csv" "${curve_args[@]}" --json "$work/pd_data.json" > "$work/pd_data.out"
check "curve --start-data on a rotation exits 0" test $? -eq 0
check "curve --start-data: the report names the data" grep -q "start data $work/pen.csv" "$work/pd_data.out"
"$bin" curve "$pen" "${curve_args[@]}" --json "$work/pd.json" > "$work/pd.out"
check "curve of the rotation's PD from [states] exits 0" test $? -eq 0
check "the two curves end at the same points" test "$(grep stopped "$work/pd_data.out")" = "$(grep stopped "$work/pd.out")"
eps=$(json_value "$work/pd.json" "repr([p for p in j['points'] if p['first'] == 0.4][0]['second'])")
"$bin" continue "$pen" --set "eps=$eps" --param ri --from 0.6 --to 0.15 --quiet --json "$work/pd_branch.json" > /dev/null
check "the curve's point at ri = 0.4 is the branch's PD at its eps" test "$(json_value "$work/pd_branch.json" "[e['type'] for e in j['events']] == ['PD'] and abs(j['events'][0]['value'] - 0.4) < 2e-9 + j['events'][0]['uncertainty']")" = True

# Bad data: each refused with exit code 2, a located error, nothing compiled and nothing computed.
bad() {  # bad NAME CONTENT EXPECTED...: orbit on lcbp from this data must fail so
  local name=$1 content=$2; shift 2
  printf '%b' "$content" > "$work/$name.csv"
  SYMPATHY_CACHE_DIR="$work/cache_bad" "$bin" orbit "$lcbp" --start-data "$work/$name.csv" \
    > "$work/$name.out" 2> "$work/$name.err"
  check "$name: exit code 2" test $? -eq 2
  for expected in "$@"; do
    check "$name: error says '$expected'" grep -qF "$expected" "$work/$name.err"
  done
  check "$name: nothing computed" test ! -s "$work/$name.out"
  check "$name: nothing compiled" test "$(ls "$work/cache_bad"/*.so 2> /dev/null | wc -l)" -eq 0
}
bad missing_column 't,x\n0,1\n0.25,0\n0.5,-1\n0.75,0\n1,1\n' "$work/missing_column.csv:1: no column 'y'; expected t and every state of $lcbp (x, y)"
bad non_monotone 't,x,y\n0,1,0\n0.25,0,1\n0.2,-1,0\n0.75,0,-1\n1,1,0\n' "$work/non_monotone.csv:4: column 't': time 0.2 after 0.25"
bad too_short 't,x,y\n0,1,0\n0.5,-1,0\n' "$work/too_short.csv: 2 rows after the header; expected at least 4"
bad half_period 't,x,y\n0,1,0\n0.125,0.7071,0.7071\n0.25,0,1\n0.375,-0.7071,0.7071\n0.5,-1,0\n' "$work/half_period.csv:6: the last row is 2 from the first" "too short?"
"$bin" orbit "$lcbp" --start-data "$work/r1.csv" --start outside > /dev/null 2> "$work/both.err"
check "--start with --start-data: exit code 2" test $? -eq 2
check "--start with --start-data: says which" grep -qF -- "--start: not with --start-data $work/r1.csv" "$work/both.err"
"$bin" continue "$lcbp" --param p1 --from 1 --to 2 --start-data "$work/missing_column.csv" > /dev/null 2> "$work/cont_bad.err"
check "continue refuses bad data the same way" grep -qF "missing_column.csv:1: no column 'y'" "$work/cont_bad.err"

# A forced system (a case file that uses t): its period is the forcing's, not the recording's;
# refused after the file is read, before any integration.
cat > "$work/forced.toml" <<'TOML'
kind = "equations"
[states]
x = 0.0
v = 0.0
[parameters]
c = 0.1
[equations]
x = "v"
v = "-c*v - x + cos(t)"
TOML
/usr/bin/python3 -c "
import math
print('t,x,v')
for k in range(41): t = 2 * math.pi * k / 40; print('%r,%r,%r' % (t, math.cos(t), -math.sin(t)))" > "$work/forced.csv"
"$bin" orbit "$work/forced.toml" --start-data "$work/forced.csv" > "$work/forced.out" 2> "$work/forced.err"
check "a forced system with --start-data: exit code 2" test $? -eq 2
check "... says why" grep -qF "forced.toml uses t (a periodically forced system), whose period is the forcing's" "$work/forced.err"
for command in orbit "continue --param c --from 0.1 --to 0.2"; do
  # shellcheck disable=SC2086
  "$bin" $command "$work/forced.toml" > /dev/null 2> "$work/forced_plain.err"
  check "a forced system without data ($command): exit code 2" test $? -eq 2
  check "... says why" grep -qF "forced.toml: its equations use t (a periodically forced system) and it declares no forcing period; expected forcing_period" "$work/forced_plain.err"
done

# continue from the data: the unstable family r = p1 from p1 = 1 to 1.8, with user points at
# 1.25 and 1.5: each event UZ at its value exactly (1e-12), its orbit the circle of radius p1,
# period 1, multiplier exp(-p1 (p1 - 2)); to 1e-8 (the integration's accuracy, rtol 5e-12).
"$bin" continue "$lcbp" --param p1 --from 1 --to 1.8 --start-data "$work/r1.csv" --user-points 1.25,1.5 \
  --quiet --json "$work/family.json" --events "$work/family_events.csv" > "$work/family.out"
check "continue --start-data --user-points exits 0" test $? -eq 0
check "two UZ at 1.25 and 1.5 exactly" test "$(json_value "$work/family.json" "[(e['type'], abs(e['value'] - v) < 1e-12) for e, v in zip(j['events'], [1.25, 1.5])]")" = "[('UZ', True), ('UZ', True)]"
check "their orbits: radius p1, period 1" test "$(json_value "$work/family.json" "all(abs(math.hypot(*e['state0']) - e['value']) < 1e-8 and abs(e['period'] - 1) < 1e-8 for e in j['events'])")" = True
check "their multipliers exp(-p1 (p1 - 2))" test "$(json_value "$work/family.json" "all(min(abs(complex(*m) - math.exp(-e['value'] * (e['value'] - 2))) for m in e['multipliers']) < 1e-8 for e in j['events'])")" = True
check "the JSON names the data" test "$(json_value "$work/family.json" "j['start_data']")" = "$work/r1.csv"
check "the events CSV has the UZ rows" test "$(grep -c '^UZ,1\.\(25\|5\),0,' "$work/family_events.csv")" -eq 2
check "the table lists them" grep -qE '^  UZ +1\.25 ' "$work/family.out"

# hopf.toml: the circles r = sqrt(mu), from the file's start, user points 0.36 and 0.64 (radii
# 0.6 and 0.8 exactly), and 1 (the bound itself: the last point).
"$bin" continue "$hopf" --param mu --from 0.25 --to 1 --user-points 0.64,0.36,1 --quiet --json "$work/hopf.json" > "$work/hopf.out"
check "hopf: three UZ in order along the branch" test "$(json_value "$work/hopf.json" "[e['value'] for e in j['events'] if e['type'] == 'UZ']")" = "[0.36, 0.64, 1.0]"
check "hopf: radii sqrt(mu), period 2 pi" test "$(json_value "$work/hopf.json" "all(abs(math.hypot(*e['state0']) - math.sqrt(e['value'])) < 1e-8 and abs(e['period'] - 2 * math.pi) < 1e-8 for e in j['events'])")" = True

# Bad user points: located, before any work.
"$bin" continue "$hopf" --param mu --from 0.25 --to 1 --user-points 0.5,abc > "$work/uz1.out" 2> "$work/uz1.err"
check "a user point not a number: exit code 2" test $? -eq 2
check "... named" grep -qF -- "--user-points 0.5,abc: 'abc' is not a finite number" "$work/uz1.err"
"$bin" continue "$hopf" --param mu --from 0.25 --to 1 --user-points 2 > "$work/uz2.out" 2> "$work/uz2.err"
check "a user point out of range: named" grep -qF -- "--user-points 2: outside --from 0.25 .. --to 1" "$work/uz2.err"
"$bin" continue "$hopf" --param mu --from 0.25 --to 1 --user-points 0.5,0.5 > "$work/uz3.out" 2> "$work/uz3.err"
check "a repeated user point: named" grep -qF -- "--user-points: expected distinct values (0.5 is given twice)" "$work/uz3.err"
check "nothing computed for them" test "$(cat "$work/uz1.out" "$work/uz2.out" "$work/uz3.out" | wc -c)" -eq 0

# Angles (cases/examples/pendulum.toml): the driven pendulum's rotation, its angle gaining 2 pi
# per period, found from rest; Liouville's multiplier exp(-gamma T) (gamma = 0.5) to 1e-8.
"$bin" orbit "$src/cases/examples/pendulum.toml" --json "$work/pendulum.json" > "$work/pendulum.out"
check "pendulum: the rotation is found" test $? -eq 0
check "pendulum: multiplier exp(-gamma T)" test "$(json_value "$work/pendulum.json" "min(abs(complex(*m) - math.exp(-0.5 * j['period'])) for m in j['multipliers']) < 1e-8")" = True
cat > "$work/bad_angle.toml" <<'TOML'
kind = "equations"
[states]
theta = { value = 0.0, angle = 1 }
omega = 0.0
[equations]
theta = "omega"
omega = "-sin(theta)"
TOML
"$bin" orbit "$work/bad_angle.toml" > /dev/null 2> "$work/bad_angle.err"
check "a bad angle declaration: exit code 2" test $? -eq 2
check "... located" grep -qF "bad_angle.toml:3: key 'states.theta.angle': expected true or false, got 1" "$work/bad_angle.err"

# A recording of an orbit of several loops starts that orbit, not its first loop's (issue 36 item
# 4): the Lorenz system at rho = 216.6 (AUTO's lor) settles on its period-4 orbit (four loops,
# T = 1.984); 2.4 time units of it recorded after a transient of 50. The first return to the
# section near the first row comes after one loop (0.477: it started the unstable period-1 orbit,
# T 0.495); the first return as near as the recording comes back at all is the period-4 orbit's.
# Its period is the period-4 branch's at rho = 216.6 (AUTO's run: PD1 of the period-2 branch born
# at PD1 of the period-1 branch; to 1e-7 relative, measured 5e-11). About 4 s.
lor=$src/tests/auto/cases/lor.toml
"$bin" simulate "$lor" --set rho=216.6 --t-end 52.5 --dt 0.001 --out "$work/lor_sim.csv" > /dev/null 2>&1
/usr/bin/python3 -c "
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
with open(sys.argv[2], 'w', newline='') as f:
    w = csv.writer(f)
    w.writerow(rows[0])
    w.writerows(r for r in rows[1:] if 50.0 <= float(r[0]) <= 52.4)" "$work/lor_sim.csv" "$work/lor_period4.csv"
"$bin" orbit "$lor" --set rho=216.6 --start-data "$work/lor_period4.csv" --json "$work/lor4.json" > /dev/null
check "a period-4 recording of lor: orbit exits 0" test $? -eq 0
"$bin" continue "$lor" --param rho --from 280 --to 200 --quiet --json "$work/lor_po.json" > /dev/null
"$bin" continue "$lor" --param rho --from 280 --to 200 --switch-at PD1 --parent "$work/lor_po.json" --quiet --json "$work/lor_pd1.json" > /dev/null
"$bin" continue "$lor" --param rho --from 280 --to 200 --switch-at PD1 --parent "$work/lor_pd1.json" --user-points 216.6 --quiet --json "$work/lor_pd2.json" > /dev/null
check "... its period the period-4 branch's at rho = 216.6 (to 1e-7 relative), stable" test "$(json_value "$work/lor4.json" "j['stable'] and any(abs(e['period'] - j['period']) < 1e-7 * j['period'] for e in json.load(open('$work/lor_pd2.json'))['events'] if e['type'] == 'UZ')")" = True

# AUTO's dat files: one period with its time scaled to [0, 1], the period given beside it
# (--data-period). The Hopf normal form's circle of radius 0.5 (mu = 0.25, w = 1), 101 rows over
# [0, 1] starting at the angle 0.3: with --data-period 2 pi the orbit, its period 2 pi and its
# radius 0.5 to 1e-9; without, Newton fails (exit 4) and says the time may be scaled; without
# --start-data the option is refused.
/usr/bin/python3 -c "
import math, sys
with open(sys.argv[1], 'w') as f:
    f.write('t,x,y\\n')
    for k in range(101):
        a = 2 * math.pi * k / 100 + 0.3
        f.write('%r,%r,%r\\n' % (k / 100, 0.5 * math.cos(a), 0.5 * math.sin(a)))" "$work/hopf_dat.csv"
"$bin" orbit "$hopf" --start-data "$work/hopf_dat.csv" --data-period 6.283185307179586 --json "$work/hopf_dat.json" > "$work/hopf_dat.out"
check "an AUTO-style dat with --data-period: orbit exits 0" test $? -eq 0
check "... the report says the time was scaled" grep -qF "its time scaled by --data-period 6.283185307179586" "$work/hopf_dat.out"
check "... period 2 pi and radius 0.5 (to 1e-9)" test "$(json_value "$work/hopf_dat.json" "abs(j['period'] - 2 * math.pi) < 1e-9 and abs(math.hypot(*j['state0']) - 0.5) < 1e-9")" = True
"$bin" orbit "$hopf" --start-data "$work/hopf_dat.csv" > "$work/hopf_dat_bare.out" 2>&1
check "... without --data-period: exit 4" test $? -eq 4
check "... saying the time may be scaled" grep -qF "give the period with --data-period" "$work/hopf_dat_bare.out"
"$bin" orbit "$hopf" --data-period 3 > /dev/null 2> "$work/dat_alone.err"
check "--data-period without --start-data: refused, exit 2" test $? -eq 2
check "... saying what it needs" grep -qF -- "--data-period 3: expected --start-data FILE too" "$work/dat_alone.err"

exit "$failures"
