#!/usr/bin/env bash
# The orbit command end to end: its report, its JSON, its exit codes.
# Usage: orbit_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
json_value() {  # json_value FILE EXPRESSION: evaluates a Python expression on the parsed JSON `j`
  /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"
}

"$bin" orbit "$src/cases/row2.toml" --start anti-phase --json "$work/anti.json" > "$work/anti.out"
check "orbit exits 0 when Newton converges" test $? -eq 0
check "report gives the period" grep -q '^  period  .* s    frequency 1.7' "$work/anti.out"
check "report marks the trivial multiplier" grep -q 'trivial$' "$work/anti.out"
check "anti-phase at Table II is unstable (paper, Sec. III)" grep -q '^  stability    unstable' "$work/anti.out"
check "report gives the accuracy figures" grep -q 'Newton residual .*trivial multiplier |mu - 1|' "$work/anti.out"
check "report gives the run time" grep -q '^  run time' "$work/anti.out"
for key in period multipliers stable trivial_multiplier_error residual state0 state_names params seconds; do
  check "JSON has '$key'" test "$(json_value "$work/anti.json" "'$key' in j")" = True
done
check "JSON: six multipliers as [re, im]" test "$(json_value "$work/anti.json" "len(j['multipliers']) == 6 and all(len(m) == 2 for m in j['multipliers'])")" = True
check "JSON: unstable" test "$(json_value "$work/anti.json" "j['stable']")" = False
check "JSON: trivial multiplier within 1e-8 of 1" test "$(json_value "$work/anti.json" "j['trivial_multiplier_error'] < 1e-8")" = True
check "JSON: state names" test "$(json_value "$work/anti.json" "','.join(j['state_names'])")" = "x,th1,th2,vx,vth1,vth2"
check "JSON: parameters of the case" test "$(json_value "$work/anti.json" "j['params']['k']")" = 14.7467
# The stiffness measured before Newton (the default preset's Adams): the report's indicator, to its
# printed digits; not stiff at Table II (0.57 in README's table, threshold 1.4).
printed=$(grep -o 'stiffness indicator [0-9.]*' "$work/anti.out" | awk '{print $3}')
check "JSON: the stiffness the report printed, not stiff" test "$(json_value "$work/anti.json" "'%.2g' % j['stiffness']['indicator'] == '$printed' and j['stiffness']['threshold'] == 1.4 and not j['stiffness']['stiff'] and j['stiffness']['bdf_steps'] > 0")" = True
"$bin" orbit "$src/cases/row2.toml" --start anti-phase --method bdf --json "$work/bdf.json" > /dev/null
check "JSON: no stiffness where the method was given (nothing measured)" test "$(json_value "$work/bdf.json" "'stiffness' in j")" = False

"$bin" orbit "$src/cases/cross4.toml" --start in-in --segments 4 --method bdf --verbose > "$work/cross.out"
check "cross in-in with 4 segments exits 0" test $? -eq 0
check "4 metronomes, BDF: the structured linear solver by default" grep -q 'BDF (structured linear solver)' "$work/cross.out"
check "cross in-in is reported as not isolated" grep -q 'not isolated' "$work/cross.out"
check "cross in-in has a structural multiplier" grep -qE '   structural( |$)' "$work/cross.out"

"$bin" orbit "$src/cases/row2.toml" --start anti-phase --method bdf --linear-solver structured --verbose > "$work/structured.out"
check "--linear-solver structured exits 0" test $? -eq 0
check "structured: anti-phase still unstable" grep -q '^  stability    unstable' "$work/structured.out"
check "the report names the linear solver" grep -q 'BDF (structured linear solver)' "$work/structured.out"
check "2 metronomes, BDF: dense by default" grep -q 'BDF (dense linear solver)' <("$bin" orbit "$src/cases/row2.toml" --start anti-phase --method bdf --verbose)
# The default accuracy preset: Adams on the augmented system (cases/cli/common.cpp).
check "the report names the method and the sensitivities" grep -q 'Adams, augmented sensitivities, rtol 5e-12' <("$bin" orbit "$src/cases/row2.toml" --start anti-phase --verbose)
check "--accuracy fast: explicit Runge-Kutta" grep -q 'ERK Dormand-Prince 5(4), augmented sensitivities, rtol 1e-08' <("$bin" orbit "$src/cases/row2.toml" --start anti-phase --accuracy fast --verbose)
"$bin" orbit "$src/cases/row2.toml" --start anti-phase --accuracy medium 2> "$work/accuracy.err"
check "--accuracy medium is refused (exit 2)" test $? -eq 2
check "and the message names the presets" grep -q -- '--accuracy medium: expected fast, default or high' "$work/accuracy.err"
"$bin" orbit "$src/cases/row2.toml" --start anti-phase --method erk --sensitivities forward 2> "$work/erk.err"
check "--method erk with forward sensitivities is refused (exit 2)" test $? -eq 2
check "and the message says why" grep -q -- '--sensitivities: expected Augmented with method ERK' "$work/erk.err"
"$bin" orbit "$src/cases/row2.toml" --start anti-phase --linear-solver lu 2> "$work/bad.err"
check "--linear-solver lu exits 2" test $? -eq 2
check "and lists the solvers" grep -q "expected dense, klu or structured" "$work/bad.err"

"$bin" orbit "$src/cases/row2.toml" > "$work/bad.out" 2> "$work/bad.err"
check "missing --start exits 2" test $? -eq 2
check "missing --start lists the starts" grep -q "expected one of: in-phase, anti-phase" "$work/bad.err"

"$bin" orbit "$src/cases/row2.toml" --start in-phase --segments 0 2> "$work/bad.err"
check "--segments 0 exits 2" test $? -eq 2

# Segments side by side: each is integrated by a flow of its own thread, restarted at each call,
# so the orbit is the same to the bit on any number of threads (only the run times differ).
"$bin" orbit "$src/cases/row2.toml" --start in-phase --segments 3 --threads 1 --json "$work/seg1.json" > /dev/null
check "--segments 3 --threads 1 exits 0" test $? -eq 0
"$bin" orbit "$src/cases/row2.toml" --start in-phase --segments 3 --threads 2 --json "$work/seg2.json" > /dev/null
check "--segments 3 --threads 2 exits 0" test $? -eq 0
check "the same orbit on one thread and on two" /usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:])
for o in (a, b):
    o.pop('seconds'); o['stiffness'].pop('seconds')  # run times, the measurement's too
sys.exit(0 if a == b and a['segments'] == 3 else 1)" "$work/seg1.json" "$work/seg2.json"
"$bin" orbit "$src/cases/row2.toml" --start in-phase --segments 3 --threads 0 2> "$work/bad.err"
check "--threads 0 exits 2" test $? -eq 2
check "and says what is expected" grep -q -- '--threads: expected an integer from 1 to 256' "$work/bad.err"

"$bin" orbit "$src/cases/cross4.toml" --start in-anti --transient 5 > "$work/quasi.out"
check "a start on no periodic orbit exits 4" test $? -eq 4
check "and says Newton failed" grep -q 'newton       FAILED' "$work/quasi.out"

# A signal during an orbit (issue 32: orbit had no signal handling): exit 6 at once, saying so,
# no JSON and no temporary left. The 64-metronome orbit in the whole state takes about 5 s; the
# signal comes 1 s in.
interrupted_after 1 "$bin" orbit "$src/cases/row/row64.toml" --start in-phase --whole-state \
  --json "$work/signal.json" > /dev/null 2> "$work/signal.err"
check "SIGINT during orbit exits 6" test $? -eq 6
check "... saying it was interrupted" grep -q "interrupted: stopped, no file written" "$work/signal.err"
check "... writing no JSON" test "$(ls "$work" | grep -c '^signal.json')" -eq 0
# A slow orbit found by a transient (issue 36: AUTO's c2c, the food chain at d1 = 0.45, period
# 66.6): past the default longest period (10 s) the start says how to raise it; --max-period 100
# finds the orbit, whose period is the HB1 family's at d1 = 0.45 (its user point, an independent
# continuation from the Hopf point: to 1e-7 relative; measured 4e-10). About 1 s with the compile.
c2c=$src/tests/auto/cases/c2c.toml
"$bin" orbit "$c2c" --set d1=0.45 --transient 5000 > "$work/c2c_short.out" 2>&1
check "c2c at d1 = 0.45 without --max-period: no return within 10 s, saying how to raise it" grep -qF "no return to the section within 10 s after the transient (an equilibrium, or a longer period? max_period, --max-period, raises the limit)" "$work/c2c_short.out"
"$bin" orbit "$c2c" --set d1=0.45 --transient 5000 --max-period 100 --json "$work/c2c.json" > /dev/null
check "... with --max-period 100 the orbit, exit 0" test $? -eq 0
"$bin" equilibria "$c2c" --param d1 --from 0.5 --to 0.6 --quiet --json "$work/c2c_eq.json" > /dev/null
"$bin" continue "$c2c" --param d1 --from 0.2 --to 0.6 --switch-at HB1 --parent "$work/c2c_eq.json" \
  --user-points 0.45 --quiet --json "$work/c2c_po.json" > /dev/null
check "... its period the HB1 family's at d1 = 0.45 (to 1e-7 relative)" test "$(json_value "$work/c2c.json" "(lambda T: any(abs(e['period'] - T) < 1e-7 * T for e in json.load(open('$work/c2c_po.json'))['events'] if e['type'] == 'UZ'))(j['period'])")" = True
# "Settled" on the orbit's own return (issue 36: AUTO's chu): at alpha = 6.9 the motion spirals
# slowly out from the equilibrium x = 1.5 onto a cycle of amplitude 0.18 in x. After the 60 s
# transient it still moves by 0.0017 in a period: 0.1% of the state's size, which the old measure
# took for nearly settled, but 0.9% of its own amplitude, which it is not; a longer transient
# settles it (period 2.06695, the HB1 family's).
chu=$src/tests/auto/cases/chu.toml
"$bin" orbit "$chu" --start nonzero --set alpha=6.9 --initial x=1.6 > "$work/chu_short.out" 2>&1
check "chu at alpha = 6.9 after 60 s: not settled, by more than 0.5% of its size (its own amplitude)" test "$(grep -oE 'moved by [0-9.e-]+ \(([0-9.]+)% of its size\)' "$work/chu_short.out" | grep -oE '\([0-9.]+' | tr -d '(' | awk '{print ($1 > 0.5)}')" = 1
"$bin" orbit "$chu" --start nonzero --set alpha=6.9 --initial x=1.6 --transient 400 --json "$work/chu.json" > /dev/null
check "... settled after a longer transient: period 2.06695" test "$(json_value "$work/chu.json" "abs(j['period'] - 2.06695) < 1e-5")" = True
# A start state with a period guess (--period-guess): Newton at once, no transient. On lcbp at
# p1 = 1, p2 = 2 the circle r = 1 repels (its multiplier exp(-p1 (p1 - p2)) = e); from (1, 0)
# with the guess 1 it is the orbit: period 1 and radius 1 to 1e-9, multiplier e to 1e-7. The
# branch in p2 from it stays on r = 1. Beside --transient it is refused.
lcbp=$src/cases/examples/lcbp.toml
"$bin" orbit "$lcbp" --initial x=1 --initial y=0 --period-guess 1 --json "$work/guess.json" > /dev/null
check "orbit with --period-guess on the unstable circle exits 0" test $? -eq 0
check "... period 1, radius 1 (to 1e-9), multiplier e (to 1e-7)" test "$(json_value "$work/guess.json" "abs(j['period'] - 1) < 1e-9 and abs((j['state0'][0]**2 + j['state0'][1]**2)**0.5 - 1) < 1e-9 and abs(max(abs(complex(*m)) for m in j['multipliers']) - 2.718281828459045) < 1e-7")" = True
"$bin" continue "$lcbp" --initial x=1 --initial y=0 --period-guess 1 --param p2 --from 2 --to 2.5 --quiet --json "$work/guess_branch.json" > /dev/null
check "... continue from it in p2: every point on r = 1 (to 1e-9)" test "$(json_value "$work/guess_branch.json" "all(abs((p['state0'][0]**2 + p['state0'][1]**2)**0.5 - 1) < 1e-9 for p in j['points'])")" = True
"$bin" orbit "$lcbp" --period-guess 1 --transient 5 > /dev/null 2> "$work/guess_transient.err"
check "--period-guess with --transient: exit 2, saying why" grep -qF -- "--period-guess 1: not with --transient" "$work/guess_transient.err"
exit $failures
