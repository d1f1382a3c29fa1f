#!/usr/bin/env bash
# Equilibria and Hopf starts end to end on AUTO's demos (cases/examples): abc's four Hopf points
# (exact values to 1e-8), its family born at the first (AUTO's folds of cycles) from equilibria
# computed or read back from JSON, the family ending at its Hopf point, a fold curve of it in two
# parameters; the metronomes' s -> 0 end; bad requests refused before any work.
# Usage: equilibria_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
export SYMPATHY_CACHE_DIR="$work/cache"  # never the user's cache
json() { /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }
abc=$src/cases/examples/abc.toml

"$bin" equilibria "$abc" --param p1 --from 0 --to 0.4 --csv "$work/eq.csv" --json "$work/eq.json" \
  > "$work/eq.out" 2> "$work/eq.err"
check "equilibria exits 0" test $? -eq 0
check "run time printed" grep -q 'run time' "$work/eq.out"
check "progress lines on stderr" grep -q '^  \[   1\] p1 = ' "$work/eq.err"
# The Hopf conditions solved directly (issue 16's reference values).
check "four Hopf points, each within 1e-8 of the exact value" test "$(json "$work/eq.json" "
[e['value'] for e in j['events'] if e['type'] == 'HB'] and all(abs(a - b) < 1e-8 for a, b in zip(
  [e['value'] for e in j['events'] if e['type'] == 'HB'],
  [0.204184536, 0.229839038, 0.259957854, 0.346208522])) and len(j['events']) == 4")" = True
check "each with omega, period 2 pi / omega and its criticality" test "$(json "$work/eq.json" "
all(abs(e['hopf']['period'] * e['hopf']['omega'] - 6.283185307179586) < 1e-12 and
    e['hopf']['criticality'].split()[0] in ('supercritical', 'subcritical') for e in j['events'])")" = True
check "the events table names HB with omega" grep -q '^  HB   0.2041845357.*omega 0.797303' "$work/eq.out"
check "CSV has a row per point" test "$(($(wc -l < "$work/eq.csv") - 1))" -eq "$(json "$work/eq.json" "len(j['points'])")"
check "CSV header: states, then eigenvalues" grep -q '^index,p1,u1,u2,u3,unstable,residual,lambda1_re' "$work/eq.csv"

# The family born at HB1, from the saved equilibria: AUTO's folds of cycles (test/hyper.all).
"$bin" continue "$abc" --param p1 --from 0.2 --to 0.25 --switch-at HB1 --parent "$work/eq.json" \
  --json "$work/hb1.json" --quiet > "$work/hb1.out" 2>&1
check "the Hopf family exits 0" test $? -eq 0
check "born at the equilibria's HB" grep -q "born at the equilibria's HB at p1 = 0.20418453" "$work/hb1.out"
check "two folds at AUTO's p1 = 0.211903 and 0.213697 (six digits)" test "$(json "$work/hb1.json" "
sorted(round(e['value'], 6) for e in j['events'] if e['type'] == 'LP') == [0.211903, 0.213697]")" = True
# The same with the equilibria computed on the way.
"$bin" continue "$abc" --param p1 --from 0.2 --to 0.25 --switch-at HB1 --quiet \
  --json "$work/hb1b.json" > /dev/null 2>&1
check "computed equilibria give the same family" test "$(json "$work/hb1b.json" "len(j['points'])")" = \
  "$(json "$work/hb1.json" "len(j['points'])")"

# The first orbit's amplitude asked for (--hopf-amplitude): the same folds from another start.
"$bin" continue "$abc" --param p1 --from 0.2 --to 0.25 --switch-at HB1 --parent "$work/eq.json" \
  --hopf-amplitude 0.005 --json "$work/hb1c.json" --quiet > /dev/null 2>&1
check "--hopf-amplitude: the same two folds" test "$(json "$work/hb1c.json" "
sorted(round(e['value'], 6) for e in j['events'] if e['type'] == 'LP') == [0.211903, 0.213697]")" = True
"$bin" continue "$abc" --param p1 --from 0.2 --to 0.25 --hopf-amplitude 0.01 > /dev/null 2> "$work/bad.err"
check "--hopf-amplitude without --switch-at HBn exits 2, saying so" \
  grep -q -- "--hopf-amplitude: only with --switch-at HBn" "$work/bad.err"

# From p1 = 0.25 down, the family ends at the Hopf point it was born at.
"$bin" continue "$abc" --param p1 --from 0.25 --to 0.2 --json "$work/down.json" --quiet \
  > "$work/down.out" 2>&1
check "the family down exits 0" test $? -eq 0
check "stopped at the Hopf point" test "$(json "$work/down.json" "
j['stop'] == 'Hopf point' and abs(j['hopf_end']['value'] - 0.204184536) < 1e-8")" = True
check "each fold once, no turn taken for a fold" test "$(json "$work/down.json" "
sorted(round(e['value'], 6) for e in j['events']) == [0.211903, 0.213697]")" = True

# The fold curve of abc's family in (p1, p3) from the saved branch (an equation case file in
# curve): where it leaves its window at p3 = 1.52 exactly, its p1 is the fold the one-parameter
# branch at p3 = 1.52 locates (1e-8: both located to about 1e-12).
"$bin" curve "$abc" --param p1 --from 0.25 --to 0.2 --parent "$work/down.json" --event LP1 \
  --second p3 --second-from 1.52 --second-to 1.56 --json "$work/lp.json" --quiet > "$work/lp.out" 2>&1
check "curve on an equation case file exits 0" test $? -eq 0
"$bin" continue "$abc" --param p1 --from 0.25 --to 0.2 --set p3=1.52 --json "$work/p3.json" \
  --quiet > /dev/null 2>&1
check "its end at p3 = 1.52 is the fold of the branch at p3 = 1.52" test "$(/usr/bin/python3 -c "
import json, sys
curve = json.load(open(sys.argv[1]))
branch = json.load(open(sys.argv[2]))
end = min(curve['points'], key=lambda p: p['second'])
folds = [e['value'] for e in branch['events'] if e['type'] == 'LP']
print(end['second'] == 1.52 and min(abs(f - end['first']) for f in folds) < 1e-8)" "$work/lp.json" "$work/p3.json")" = True

# The metronomes (the reliability issue's s -> 0 branch): the in-phase orbit shrinks into the
# hanging equilibrium as the escapement torque s goes to 0, and its branch ends at the in-phase
# mode's Hopf point near s = 2.4e-9 N m (no fold, no retrace); the equilibria have it too, beside
# the anti-phase mode's.
row2=$src/cases/row2.toml
"$bin" continue "$row2" --start in-phase --param s --from 4.51e-5 --to 0 --json "$work/s.json" \
  --quiet > "$work/s.out" 2>&1
check "the s -> 0 branch exits 0" test $? -eq 0
check "it ends at the Hopf point at s = 2.40e-9 N m, with no event" test "$(json "$work/s.json" "
j['stop'] == 'Hopf point' and abs(j['hopf_end']['value'] - 2.4011e-9) < 1e-12 and not j['events']")" = True
"$bin" equilibria "$row2" --start in-phase --param s --from 1e-8 --to 0 --json "$work/s_eq.json" \
  --quiet > /dev/null 2>&1
check "the hanging equilibria: two Hopf points, the in-phase one where the branch ended" \
  test "$(json "$work/s_eq.json" "
len(j['events']) == 2 and min(abs(e['value'] - $(json "$work/s.json" "j['hopf_end']['value']")) for e in j['events']) < 1e-20")" = True

# A restart from a saved equilibrium (AUTO's IRS with a label): abc's equilibria with a user point
# at p1 = 0.3 (UZ1), continued from there in p3 to 1.7 and back through p3 = 1.55, where the
# equilibrium is the p1 run's at 0.3 (its second user point, to 1e-9; the state exact at each).
"$bin" equilibria "$abc" --param p1 --from 0 --to 0.4 --user-points 0.3 --quiet --json "$work/uz.json" > /dev/null
"$bin" equilibria "$abc" --parent "$work/uz.json" --from-point UZ1 --param p3 --from 1.7 --to 1.4 \
  --user-points 1.55 --quiet --json "$work/from_uz.json" > "$work/from_uz.out"
check "equilibria --from-point UZ1: exit 0, the start named" grep -qF "start saved $work/uz.json, UZ1 (p1 = 0.3)" "$work/from_uz.out"
check "... its equilibrium at p3 = 1.55 the p1 run's at 0.3 (1e-9)" test "$(json "$work/from_uz.json" "max(abs(a - b) for a, b in zip([e for e in j['events'] if e['type'] == 'UZ'][0]['state'], [e for e in json.load(open('$work/uz.json'))['events'] if e['type'] == 'UZ'][0]['state'])) < 1e-9")" = True
"$bin" equilibria "$abc" --parent "$work/uz.json" --from-point XY1 --param p3 --from 1.7 --to 1.4 \
  > /dev/null 2> "$work/bad_point.err"
check "... an event it does not have exits 2, listing its events" grep -qF -- "--from-point XY1: $work/uz.json has no such point or event; expected a point's index or one of its events: HB1, HB2, HB3, UZ1, HB4" "$work/bad_point.err"

# Switching at a branch point of equilibria (AUTO's lrz.auto): the Lorenz origin loses stability
# at rho = 1, where the nonzero equilibria x = y = +-sqrt(beta (rho - 1)), z = rho - 1 are born
# (a pitchfork); both halves from one switch, each with its Hopf point at rho = sigma (sigma +
# beta + 3) / (sigma - beta - 1) = 24.736842105 (1e-8; every point on the closed form to 1e-9).
lrz=$src/cases/examples/lrz.toml
"$bin" equilibria "$lrz" --param rho --from 0 --to 30 --initial x=0 --initial y=0 --initial z=0 \
  --quiet --json "$work/lrz0.json" > /dev/null
"$bin" equilibria "$lrz" --param rho --from 0 --to 30 --switch-at BP1 --parent "$work/lrz0.json" \
  --quiet --json "$work/lrz1.json" > "$work/lrz1.out"
check "equilibria --switch-at BP1 exits 0, naming the branch point" grep -q "born at the parent branch's BP at rho = 1" "$work/lrz1.out"
check "... both halves on the closed form (1e-9) to rho = 30" test "$(json "$work/lrz1.json" "
all(abs(p['state'][0]**2 - 8/3*(p['value'] - 1)) < 1e-9 and abs(p['state'][2] - p['value'] + 1) < 1e-9
    for p in j['points']) and max(p['value'] for p in j['points']) == 30 and
min(p['state'][0] for p in j['points']) < -8 < 8 < max(p['state'][0] for p in j['points'])")" = True
check "... a Hopf point on each half at the exact rho_H (1e-8)" test "$(json "$work/lrz1.json" "
[round(e['state'][0]) for e in j['events']] == [-8, 8] and
all(e['type'] == 'HB' and abs(e['value'] - 24.736842105263158) < 1e-8 for e in j['events'])")" = True
"$bin" equilibria "$lrz" --param rho --from 0 --to 30 --initial x=0 --initial y=0 --initial z=0 \
  --switch-at BP1 --quiet --json "$work/lrz1c.json" > /dev/null
check "... the same with the parent computed on the way" test "$(json "$work/lrz1c.json" "
[e['value'] for e in j['events']] == [e['value'] for e in json.load(open('$work/lrz1.json'))['events']]")" = True
"$bin" equilibria "$lrz" --param rho --from 0 --to 30 --switch-at HB1 > /dev/null 2> "$work/bad.err"
check "equilibria --switch-at HB1 exits 2, pointing to continue" grep -q -- "--switch-at HB1: expected a branch point of the equilibria.*continue --switch-at HB1" "$work/bad.err"
"$bin" equilibria "$lrz" --param rho --from 0 --to 30 --switch-at BP2 --parent "$work/lrz0.json" \
  > /dev/null 2> "$work/bad.err"
check "a BP the parent lacks exits 2, counting its BPs" grep -qF -- "--switch-at BP2: --parent $work/lrz0.json has 1 branch point(s); expected BP1 .. BP1" "$work/bad.err"
"$bin" equilibria "$lrz" --param sigma --from 5 --to 15 --switch-at BP1 --parent "$work/lrz0.json" \
  > /dev/null 2> "$work/bad.err"
check "a parent in another parameter exits 2" grep -q -- "equilibria in rho; expected them in --param sigma" "$work/bad.err"
"$bin" equilibria "$lrz" --param rho --from 0 --to 30 --at 10 --switch-at BP1 > /dev/null 2> "$work/bad.err"
check "--at beside --switch-at exits 2" grep -q -- "--at: not with --switch-at BP1" "$work/bad.err"

# The Hopf curve of Lorenz's nonzero equilibria in (rho, sigma) from the switched run's HB2:
# rho_H(sigma) = sigma (sigma + beta + 3) / (sigma - beta - 1) at every point (1e-9 relative),
# omega^2 = kappa; CSV a row per point.
"$bin" curve "$lrz" --parent "$work/lrz1.json" --event HB2 --param rho --from 0 --to 200 \
  --second sigma --second-from 5 --second-to 30 --quiet --json "$work/lrz_h.json" \
  --csv "$work/lrz_h.csv" > "$work/lrz_h.out"
check "curve --parent EQUILIBRIA.json --event HB2 exits 0" test $? -eq 0
check "... every point on rho_H(sigma) (1e-9 relative), both ends on the sigma window" test "$(json "$work/lrz_h.json" "
all(abs(p['first'] - p['second'] * (p['second'] + 8/3 + 3) / (p['second'] - 8/3 - 1)) < 1e-9 * p['first'] and
    abs(p['omega']**2 - p['kappa']) < 1e-9 * p['kappa'] for p in j['points']) and
sorted(p['second'] for p in j['points'])[::len(j['points']) - 1] == [5, 30] and j['of'] == 'equilibria'")" = True
check "... CSV a row per point" test "$(($(wc -l < "$work/lrz_h.csv") - 1))" -eq "$(json "$work/lrz_h.json" "len(j['points'])")"
"$bin" curve "$lrz" --parent "$work/lrz1.json" --event BP1 --param rho --from 0 --to 200 \
  --second sigma --second-from 5 --second-to 30 > /dev/null 2> "$work/bad.err"
check "a curve from an equilibria BP exits 2" grep -q -- "--event BP1: expected a fold or Hopf point of the equilibria" "$work/bad.err"
"$bin" curve "$lrz" --parent "$work/lrz1.json" --event HB3 --param rho --from 0 --to 200 \
  --second sigma --second-from 5 --second-to 30 > /dev/null 2> "$work/bad.err"
check "... from a Hopf point they lack exits 2" grep -qF -- "--event HB3: --parent $work/lrz1.json has 2 HB point(s)" "$work/bad.err"
"$bin" curve "$lrz" --parent "$work/lrz1.json" --event HB1 --param rho --from 0 --to 200 \
  --second rho --second-from 5 --second-to 30 > /dev/null 2> "$work/bad.err"
check "... in its own parameter exits 2" grep -q -- "--second rho: expected a parameter other than --param" "$work/bad.err"
"$bin" curve "$lrz" --parent "$work/lrz1.json" --event HB1 --param rho --from 0 --to 200 \
  --second sigma --second-from 12 --second-to 30 > /dev/null 2> "$work/bad.err"
check "... with a window that does not hold the start exits 2" grep -q -- "the window does not hold the equilibria's sigma = 10" "$work/bad.err"

# The family of orbits born at any point of a Hopf curve (continue --parent HOPF.json
# --from-point N): the Hopf normal form's Hopf curve mu = 0 in (mu, w), its point N at w = w_N
# starts the circles of period 2 pi / w_N (1e-8 relative; measured 1.4e-10) and radius sqrt(mu)
# (1e-7; measured 4e-8 at mu = 2.5e-3, where the orbits are 0.05 across).
cat > "$work/hopf_free.toml" <<'TOML'
kind = "equations"
name = "hopf_free"
[states]
x = 0.0
y = 0.0
[parameters]
mu = -0.5
w = 1.0
[intermediates]
r2 = "x^2 + y^2"
[equations]
x = "mu*x - w*y - x*r2"
y = "w*x + mu*y - y*r2"
TOML
"$bin" equilibria "$work/hopf_free.toml" --param mu --from -0.5 --to 0.5 --quiet --json "$work/hf_eq.json" > /dev/null
"$bin" curve "$work/hopf_free.toml" --parent "$work/hf_eq.json" --event HB1 --param mu --from -1 --to 1 \
  --second w --second-from 0.5 --second-to 3 --quiet --json "$work/hf_curve.json" > /dev/null
n=$(json "$work/hf_curve.json" "max(j['points'], key=lambda p: p['second'])['index']")
"$bin" continue "$work/hopf_free.toml" --parent "$work/hf_curve.json" --from-point "$n" --param mu \
  --from 0 --to 0.5 --quiet --json "$work/hf_family.json" > "$work/hf_family.out"
check "continue --parent HOPF_CURVE.json --from-point N: the family born there, named" grep -q "start the Hopf point $n of the Hopf curve" "$work/hf_family.out"
check "... circles of period 2 pi / w_N (1e-8) and radius sqrt(mu) (1e-7)" test "$(json "$work/hf_family.json" "
(lambda math: len(j['points']) > 5 and all(abs(p['period'] - 2 * math.pi / 3) < 1e-8 * p['period'] and
abs(math.hypot(*p['state0']) - math.sqrt(p['value'])) < 1e-7 for p in j['points'] if p['value'] > 1e-3))(__import__('math'))")" = True

# The Bautin normal form (cases/examples/bautin.toml): the generalized Hopf point of its Hopf
# curve b1 = 0 at the origin with l2 = -4 (1e-6), and the fold of cycles born there (curve
# --parent HOPF_CURVE.json --event GH1) on b1 = -b2^2 / 4 (1e-8), ended near GH on one side and
# at the window on the other.
bautin=$src/cases/examples/bautin.toml
"$bin" equilibria "$bautin" --param b1 --from -0.5 --to 0.5 --quiet --json "$work/ba_eq.json" > /dev/null
"$bin" curve "$bautin" --parent "$work/ba_eq.json" --event HB1 --param b1 --from -1 --to 1 \
  --second b2 --second-from -1 --second-to 1 --quiet --json "$work/ba_hb.json" > /dev/null
check "the Bautin form's GH at the origin with l2 = -4 (1e-6)" test "$(json "$work/ba_hb.json" "
[(abs(e['first']) < 1e-8 and abs(e['second']) < 1e-8 and abs(e['coefficients']['l2'] + 4) < 4e-6)
 for e in j['events'] if e['type'] == 'GH'] == [True]")" = True
"$bin" curve "$bautin" --parent "$work/ba_hb.json" --event GH1 --param b1 --from -1 --to 0.1 \
  --second b2 --second-from -1 --second-to 0.5 --quiet --json "$work/ba_lpc.json" \
  --csv "$work/ba_lpc.csv" > "$work/ba_lpc.out"
check "curve --event GH1: the fold of cycles born there, exit 0" test $? -eq 0
check "... the family it started from named, l2's side" grep -q "l2 = -4, a fold of cycles where l1 > 0" "$work/ba_lpc.out"
check "... every point on b1 = -b2^2 / 4 (1e-8), from near GH to the window" test "$(json "$work/ba_lpc.json" "
j['kind'] == 'LP' and all(abs(p['first'] + p['second']**2 / 4) < 1e-8 for p in j['points']) and
min(p['second'] for p in j['points']) < 0.02 and max(p['second'] for p in j['points']) == 0.5")" = True
check "... ended near the generalized Hopf point" grep -q "backward: ended near the generalized Hopf point at b1 = 0, b2 = 0" "$work/ba_lpc.out"
check "... CSV a row per point" test "$(($(wc -l < "$work/ba_lpc.csv") - 1))" -eq "$(json "$work/ba_lpc.json" "len(j['points'])")"
"$bin" curve "$bautin" --parent "$work/ba_hb.json" --event GH1 --param b1 --from -1 --to 0.1 \
  --second b2 --second-from -1 --second-to 0.5 --user-value b1=-0.01 --stop-at b2=0.3 --quiet \
  --json "$work/ba_stop.json" > /dev/null
check "... --user-value b1=-0.01 and --stop-at b2=0.3: UZ at b2 = 0.2 and the end at b1 = -0.0225 (1e-8)" test "$(json "$work/ba_stop.json" "
[e['type'] for e in j['events']] == ['UZ', 'UZ'] and all(abs(e['first'] - a) < 1e-8 and abs(e['second'] - b) < 1e-8
for e, (a, b) in zip(j['events'], [(-0.01, 0.2), (-0.0225, 0.3)])) and max(p['second'] for p in j['points']) <= 0.3 + 1e-8")" = True
"$bin" curve "$bautin" --parent "$work/ba_hb.json" --event GH2 --param b1 --from -1 --to 0.1 \
  --second b2 --second-from -1 --second-to 0.5 > /dev/null 2> "$work/bad.err"
check "a GH the Hopf curve lacks exits 2" grep -qF -- "--event GH2: $work/ba_hb.json has 1 GH point" "$work/bad.err"
"$bin" curve "$bautin" --parent "$work/ba_hb.json" --event HB1 --param b1 --from -1 --to 0.1 \
  --second b2 --second-from -1 --second-to 0.5 > /dev/null 2> "$work/bad.err"
check "... an HB of a Hopf curve exits 2, listing what is expected" grep -q -- "--event HB1: .* is a curve of equilibria; expected one of its codimension-two points, BT, CP, GH, ZH or HH" "$work/bad.err"
"$bin" curve "$bautin" --parent "$work/ba_hb.json" --event GH1 --param b2 --from -1 --to 0.1 \
  --second b1 --second-from -1 --second-to 0.5 > /dev/null 2> "$work/bad.err"
check "... parameters swapped exits 2" grep -q -- "is a Hopf curve in b1 and b2; expected --param b1 --second b2" "$work/bad.err"

# The curve through a codimension-two point (curve --parent CURVE.json --event BT1): the
# Bogdanov-Takens form's BT on its Hopf curve b1 = 0 starts the fold curve b1 = b2^2 / 4 (1e-9).
bt=$src/cases/examples/bt.toml
"$bin" equilibria "$bt" --param b1 --from 0.1 --to -0.1 --quiet --json "$work/bt_eq.json" > /dev/null
"$bin" curve "$bt" --parent "$work/bt_eq.json" --event HB1 --param b1 --from -1 --to 1 \
  --second b2 --second-from -1.5 --second-to 1 --quiet --json "$work/bt_hb.json" > /dev/null
"$bin" curve "$bt" --parent "$work/bt_hb.json" --event BT1 --param b1 --from -1 --to 1 \
  --second b2 --second-from -1.5 --second-to 1 --quiet --json "$work/bt_lp.json" > "$work/bt_lp.out"
check "curve --parent HOPF_CURVE.json --event BT1: the fold curve, exit 0" test $? -eq 0
check "... on b1 = b2^2 / 4 (1e-9) across the window, its start not reported again" test "$(json "$work/bt_lp.json" "
j['kind'] == 'LP' and all(abs(p['first'] - p['second']**2 / 4) < 1e-9 for p in j['points']) and
sorted(p['second'] for p in j['points'])[::len(j['points']) - 1] == [-1.5, 1] and j['events'] == []")" = True
"$bin" curve "$bt" --parent "$work/bt_hb.json" --event BT2 --param b1 --from -1 --to 1 \
  --second b2 --second-from -1.5 --second-to 1 > /dev/null 2> "$work/bad.err"
check "... a BT the curve lacks exits 2" grep -qF -- "--event BT2: $work/bt_hb.json has 1 BT point" "$work/bad.err"

# The reference normal forms of cases/examples, each on its closed form: the cusp's folds on
# 27 b1^2 = 4 b2^3 (1e-9) with CP at the origin, c = -1 (1e-6); the fold-Hopf form's Hopf curve
# b1 = -b2^2 with ZH at the origin, and the fold curve b1 = 0 from it; the two oscillators' Hopf
# curve b1 = 0 with HH at the origin, and the other pair's b2 = 0 (omega sqrt 2) from it.
ex=$src/cases/examples
two="--from -2 --to 2 --second b2 --quiet"
"$bin" equilibria "$ex/cusp.toml" --param b1 --from -1 --to 1 --quiet --json "$work/cu_eq.json" > /dev/null
"$bin" curve "$ex/cusp.toml" --parent "$work/cu_eq.json" --event LP1 --param b1 $two \
  --second-from -0.3 --second-to 0.6 --json "$work/cu_lp.json" > /dev/null
check "cusp: folds on 27 b1^2 = 4 b2^3, CP at the origin with c = -1" test "$(json "$work/cu_lp.json" "
all(abs(27 * p['first']**2 - 4 * p['second']**3) < 1e-9 for p in j['points']) and
[(abs(e['first']) < 1e-8 and abs(e['second']) < 1e-8 and abs(e['coefficients']['c'] + 1) < 1e-6)
 for e in j['events']] == [True]")" = True
"$bin" equilibria "$ex/fold_hopf.toml" --param b1 --from -0.5 --to -0.01 --quiet --json "$work/fh_eq.json" > /dev/null
"$bin" curve "$ex/fold_hopf.toml" --parent "$work/fh_eq.json" --event HB1 --param b1 $two \
  --second-from -0.5 --second-to 0.5 --json "$work/fh_hb.json" > /dev/null
"$bin" curve "$ex/fold_hopf.toml" --parent "$work/fh_hb.json" --event ZH1 --param b1 $two \
  --second-from -0.5 --second-to 0.5 --json "$work/fh_lp.json" > /dev/null
check "fold-Hopf: Hopf curve b1 = -b2^2, ZH at the origin, the fold curve b1 = 0 from it" test "$(json "$work/fh_hb.json" "
all(abs(p['first'] + p['second']**2) < 1e-9 for p in j['points']) and
[(e['type'], abs(e['first']) < 1e-8 and abs(e['second']) < 1e-8) for e in j['events']] == [('ZH', True)]")$(json "$work/fh_lp.json" "
j['kind'] == 'LP' and len(j['points']) > 5 and all(abs(p['first']) < 1e-9 for p in j['points'])")" = TrueTrue
"$bin" equilibria "$ex/double_hopf.toml" --param b1 --from -0.5 --to 0.5 --quiet --json "$work/dh_eq.json" > /dev/null
"$bin" curve "$ex/double_hopf.toml" --parent "$work/dh_eq.json" --event HB1 --param b1 $two \
  --second-from -0.5 --second-to 0.5 --json "$work/dh_hb.json" > /dev/null
"$bin" curve "$ex/double_hopf.toml" --parent "$work/dh_hb.json" --event HH1 --param b1 $two \
  --second-from -0.5 --second-to 0.5 --json "$work/dh_hb2.json" > /dev/null
check "double Hopf: HH at the origin, the other pair's Hopf curve b2 = 0 with omega sqrt 2" test "$(json "$work/dh_hb.json" "
[(e['type'], abs(e['first']) < 1e-8 and abs(e['second']) < 1e-8) for e in j['events']] == [('HH', True)]")$(json "$work/dh_hb2.json" "
j['kind'] == 'HB' and len(j['points']) > 5 and
all(abs(p['second']) < 1e-9 and abs(p['omega'] - 2**0.5) < 1e-9 for p in j['points'])")" = TrueTrue

# Bad requests: named, exit 2, before any work.
"$bin" equilibria "$abc" --param p9 --from 0 --to 1 > /dev/null 2> "$work/bad.err"
check "an unknown parameter exits 2" test $? -eq 2
check "... naming the known ones" grep -q -- "--param p9: not a parameter of .*abc.toml; expected one of: p1" "$work/bad.err"
"$bin" equilibria "$abc" --param p1 --from 0 --to 0.4 --max-step 0.001 > /dev/null 2> "$work/bad.err"
check "a largest step below the first exits 2" grep -q -- "--max-step: expected a number at least the initial step" "$work/bad.err"
"$bin" continue "$abc" --param p1 --from 0.2 --to 0.25 --switch-at HB0 > /dev/null 2> "$work/bad.err"
check "HB0 exits 2 saying what is expected" grep -q -- "--switch-at HB0: expected HB followed by a positive number" "$work/bad.err"
"$bin" continue "$abc" --param p1 --from 0.2 --to 0.25 --switch-at HB7 --parent "$work/eq.json" \
  > /dev/null 2> "$work/bad.err"
check "a Hopf point the equilibria do not have exits 2, listing theirs" \
  grep -q -- "--switch-at HB7: the equilibria have no such Hopf point; they have HB1 at 0.2041" "$work/bad.err"
"$bin" continue "$abc" --param p1 --from 0.2 --to 0.25 --switch-at HB1 --parent "$work/hb1.json" \
  > /dev/null 2> "$work/bad.err"
check "a branch JSON as --parent of an HB switch exits 2" \
  grep -q -- "key 'kind' is missing; expected equilibria written by sympathy equilibria --json" "$work/bad.err"
"$bin" equilibria "$abc" --param p1 --from 0 --to 0.4 --json "$abc" > /dev/null 2> "$work/bad.err"
check "the case file as --json exits 2" test $? -eq 2
exit "$failures"
