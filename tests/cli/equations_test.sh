#!/usr/bin/env bash
# Equation case files in the commands: simulate and orbit on cases/examples, CSV columns from the
# file's names, the cache (compiled once, then reused), located errors before any compiling.
# Usage: equations_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
export SYMPATHY_CACHE_DIR="$work/cache"  # never the user's cache
json_value() {
  /usr/bin/python3 -c "import json,math,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"
}

"$bin" simulate "$src/cases/examples/hopf.toml" --t-end 20 --out "$work/hopf.csv" 2> "$work/sim.err"
check "simulate on an equation case file exits 0" test $? -eq 0
check "CSV columns are the file's states" test "$(head -1 "$work/hopf.csv")" = "t,x,y"
check "the first run compiles the system" grep -q 'system compiled in' "$work/sim.err"
check "the cache holds one entry" test "$(ls "$work/cache"/*.so | wc -l)" -eq 1
# The circle r = sqrt(mu) = 0.5 (cases/examples/hopf.toml), reached from r = 0.3 by t = 20
# (the radius converges like exp(-2 mu t) = exp(-10)): within 1e-3.
check "simulate reaches the circle r = 0.5" /usr/bin/python3 -c "
import csv,math,sys
rows=list(csv.reader(open(sys.argv[1])))[1:]
t,x,y=map(float,rows[-1])
sys.exit(0 if abs(math.hypot(x,y)-0.5) < 1e-3 and t == 20 else 1)" "$work/hopf.csv"

"$bin" orbit "$src/cases/examples/hopf.toml" --set mu=0.16 --json "$work/hopf.json" > "$work/orbit.out"
check "orbit exits 0" test $? -eq 0
check "the second run takes the system from the cache" grep -q 'system from the cache' "$work/orbit.out"
# Exact: T = 2 pi / w = 6.283185307, multiplier exp(-4 pi mu / w) = exp(-0.64 pi) = 0.133888;
# radius sqrt(0.16) = 0.4; to 1e-8 (the orbit's residual is 1e-12).
check "period 2 pi" test "$(json_value "$work/hopf.json" "abs(j['period'] - 6.283185307179586) < 1e-8")" = True
check "multiplier exp(-4 pi mu / w)" test "$(json_value "$work/hopf.json" "min(abs(complex(*m) - math.exp(-0.64 * math.pi)) for m in j['multipliers']) < 1e-8")" = True
# Amplitudes from 800 samples of the period: the peak missed by at most (pi/800)^2/2 = 7.7e-6.
check "amplitudes named after the states" test "$(json_value "$work/hopf.json" "abs(j['amplitudes']['x'] - 0.4) < 1e-5")" = True
check "JSON state names are the file's" test "$(json_value "$work/hopf.json" "','.join(j['state_names'])")" = "x,y"

"$bin" orbit "$src/cases/examples/lcbp.toml" > "$work/lcbp.out"
check "lcbp: the circle r = 2 has period 1" grep -q '^  period       1 s' "$work/lcbp.out"
# Radial multiplier exp(-p (p - p1)) of the circle r = p = p2 = 2 at p1 = 1: exp(-2) = 0.135335283.
check "lcbp: its multiplier exp(-2)" grep -q '^    0.13533528' "$work/lcbp.out"

# abc at p1 = 0.25 (the file's value), the stable orbit of the family born at the first Hopf
# point: T = 6.53496 in AUTO-07p's regression log (test/hyper.all; trust about 1e-4 relative at
# its NTST 25), here to the digits AUTO prints.
"$bin" orbit "$src/cases/examples/abc.toml" --json "$work/abc.json" > "$work/abc.out"
check "abc: orbit exits 0" test $? -eq 0
check "abc at p1 = 0.25: T = 6.53496 (AUTO-07p)" test "$(json_value "$work/abc.json" "round(j['period'], 5)")" = 6.53496

cat > "$work/bad.toml" <<'TOML'
kind = "equations"
[states]
x = 1.0
[parameters]
a = 1.0
[equations]
x = 'a*x; system("touch SMUGGLED")'
TOML
"$bin" simulate "$work/bad.toml" 2> "$work/bad.err"
check "a bad file exits 2" test $? -eq 2
check "its error is located and says what was expected" grep -q "bad.toml:7:9: key 'equations.x': expected an operator (+ - \* / ^) or the end of the expression, got ';'" "$work/bad.err"
check "nothing was compiled for it" test "$(ls "$work/cache"/*.so | wc -l)" -eq 3
check "nothing ran" test ! -e SMUGGLED -a ! -e "$work/SMUGGLED"

# continue: lcbp along the circle r = p2 = 2 from p1 = 1 to 3 meets the circle r = p1 at the
# branch point p1 = 2 exactly (cases/examples/lcbp.toml): located on the regular branch-point
# system to 1e-9 and within its reported uncertainty (measured 1.4e-11 off, +- 4.2e-11; the
# crossing alone gave 1.8e-8 off, +- 1.0e-8).
"$bin" continue "$src/cases/examples/lcbp.toml" --param p1 --from 1 --to 3 --quiet --json "$work/lcbp.json" > "$work/lcbp_branch.out"
check "continue on an equation case file exits 0" test $? -eq 0
check "lcbp: one event, a BP at p1 = 2 (1e-9, within its uncertainty)" test "$(json_value "$work/lcbp.json" "[(e['type'], abs(e['value'] - 2) < 1e-9 and abs(e['value'] - 2) <= e['uncertainty']) for e in j['events']]")" = "[('BP', True)]"
check "lcbp: the period stays 1 along r = 2" test "$(json_value "$work/lcbp.json" "max(abs(p['period'] - 1) for p in j['points']) < 1e-8")" = True
# Switching at that BP lands on the other family, the circle r = p1: every point's radius is its
# p1 (to 1e-8; measured 5.5e-9 at most), on both sides of the branch point.
"$bin" continue "$src/cases/examples/lcbp.toml" --param p1 --from 1 --to 3 --switch-at BP1 --quiet --json "$work/lcbp_born.json" > /dev/null
check "lcbp: switching at BP1 exits 0" test $? -eq 0
check "lcbp: the born branch is the circle r = p1, both sides" test "$(json_value "$work/lcbp_born.json" "max(abs(math.hypot(*p['state0']) - p['value']) for p in j['points']) < 1e-8 and min(p['value'] for p in j['points']) < 1.5 < 2.5 < max(p['value'] for p in j['points'])")" = True
# abc from p1 = 0.25 down to 0.205: the folds of AUTO-07p's log (test/hyper.all) at
# p1 = 0.213697 (T 7.61104) and 0.211903 (T 8.28914), to the digits AUTO prints (its trust: about
# 1e-4 relative at NTST 25; the periods here are 7.611039 and 8.289204).
"$bin" continue "$src/cases/examples/abc.toml" --param p1 --from 0.25 --to 0.205 --quiet --json "$work/abc_branch.json" > "$work/abc_branch.out"
check "abc: two folds at AUTO's p1" test "$(json_value "$work/abc_branch.json" "sorted(round(e['value'], 6) for e in j['events'] if e['type'] == 'LP')")" = "[0.211903, 0.213697]"
check "abc: their periods to 1e-4 relative" test "$(json_value "$work/abc_branch.json" "sorted(round(e['period'], 3) for e in j['events'] if e['type'] == 'LP')")" = "[7.611, 8.289]"

"$bin" continue "$src/cases/examples/hopf.toml" --param mu --from 0.25 --to -1 --quiet 2> "$work/cont.err"
check "a continuation range outside the parameter's bounds is refused" grep -q -- "--to -1: expected a value of mu within \[0, inf\]" "$work/cont.err"
cat > "$work/study.toml" <<TOML
title = "hopf"
case = "$src/cases/examples/hopf.toml"
parameter = "mu"
axis = "frequency"
[[branches]]
name = "hopf"
start = "outside"
from = 0.25
to = 0.1
[[branches]]
name = "fast"
start = "outside"
from = 0.25
to = 0.1
set = { w = 2.0 }
TOML
"$bin" study "$work/study.toml" --out "$work/study" > "$work/study.out" 2> "$work/study.err"
check "study on an equation case file exits 0" test $? -eq 0
# The circle's period 2 pi / w on each branch, the second with its own w = 2 (a branch's set).
check "each branch with its own parameter values: T = 2 pi and pi" test "$(json_value "$work/study/study.json" "
all(abs(p['period'] - 2 * math.pi / w) < 1e-8 for b, w in zip(j['branches'], (1, 2)) for p in b['points'])")" = True
# The row setup as equations (cases/examples/row2_equations.toml, the escapement's switch declared
# in [steep]) finds the anti-phase orbit's branch point of Table II where the built-in model does,
# within their reported uncertainties.
for f in "$src/cases/examples/row2_equations.toml" "$src/cases/row2.toml"; do
  "$bin" continue "$f" --start anti-phase --param k --from 46.5 --to 47.5 --quiet \
    --json "$work/$(basename "$f" .toml)_bp.json" > /dev/null 2>&1
done
check "the metronomes as equations: the same BP as the built-in model" test "$(/usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f))['events'] for f in sys.argv[1:3])
print(len(a) == 1 and len(b) == 1 and a[0]['type'] == b[0]['type'] == 'BP' and
      abs(a[0]['value'] - b[0]['value']) <= a[0]['uncertainty'] + b[0]['uncertainty'])" \
  "$work/row2_equations_bp.json" "$work/row2_bp.json")" = True
# A C++ plug-in (cases/examples/vdp_plugin.toml names vdp_plugin.cpp): compiled like generated
# code, and said to be code each time it runs; the van der Pol cycle at mu = 0.1, period
# 2 pi (1 + mu^2/16) = 6.28711 (Lindstedt-Poincare, to 1e-6).
"$bin" orbit "$src/cases/examples/vdp_plugin.toml" --json "$work/vdp.json" > "$work/vdp.out" 2>&1
check "orbit on a plug-in case file exits 0" test $? -eq 0
check "... saying a plug-in is code" grep -q "plug-in .*vdp_plugin.cpp compiled in .*a plug-in is C++ code" "$work/vdp.out"
check "... and its period is van der Pol's" test "$(json_value "$work/vdp.json" "abs(j['period'] - 6.287111) < 2e-6")" = True
# The rms per state, exact on van der Pol: x'' = mu (1 - x^2) x' - x gives, integrated by parts
# over a period, int x'^2 dt = int x^2 dt (the rest is the derivative of mu (x^2/2 - x^4/4)), so
# rms x = rms y (y = x') to the integration's and the trapezoidal rule's accuracy (1e-8).
check "... its rms of x and y equal" test "$(json_value "$work/vdp.json" "abs(j['rms']['x'] - j['rms']['y']) < 1e-8 and abs(j['rms']['x'] - 1.41443) < 1e-5")" = True

# AUTO-07p's ffn (cases/examples/ffn.toml): FitzHugh-Nagumo forced at beta = 10, period 2 pi / 10
# declared by forcing_period. Its torus (NS) points, AUTO's log test/hyper.all: a = 0.422945 at
# amp = 0.1 and amp = 4.52337 at a = 0, to the digits AUTO prints; at each the root mean square
# of x over the period is sqrt(1 - b / c^2) = sqrt(1 - 0.8 / 9) exactly (the multipliers'
# product exp(integral of c (1 - x^2) - b / c) is 1 there), here to 1e-7 (the location's
# uncertainty, 1e-8 in the parameter, and the describer's rtol 1e-9 integration).
ffn=$src/cases/examples/ffn.toml
rms_exact=0.9545214042184236
"$bin" orbit "$ffn" --json "$work/ffn_orbit.json" > "$work/ffn_orbit.out"
check "ffn: orbit of a forced system exits 0" test $? -eq 0
check "ffn: its period is the forcing's, 2 pi / 10" test "$(json_value "$work/ffn_orbit.json" "j['period'] == 2 * math.pi / 10")" = True
check "ffn: no trivial multiplier said" grep -q "a forced orbit, period the forcing's: no trivial multiplier" "$work/ffn_orbit.out"
"$bin" continue "$ffn" --param a --from 0 --to 1 --quiet --json "$work/ffn_a.json" > "$work/ffn_a.out"
check "ffn: continue in a exits 0" test $? -eq 0
check "ffn: one NS in a, at 0.422945 (AUTO-07p)" test "$(json_value "$work/ffn_a.json" "[(e['type'], round(e['value'], 6)) for e in j['events']]")" = "[('NS', 0.422945)]"
check "ffn: rms of x at that NS = sqrt(1 - b/c^2)" test "$(json_value "$work/ffn_a.json" "abs(j['events'][0]['rms'][0] - $rms_exact) < 1e-7")" = True
"$bin" continue "$ffn" --param amp --from 0.1 --to 10 --quiet --json "$work/ffn_amp.json" > "$work/ffn_amp.out"
check "ffn: one NS in amp, at 4.52337 (AUTO-07p)" test "$(json_value "$work/ffn_amp.json" "[(e['type'], round(e['value'], 5)) for e in j['events']]")" = "[('NS', 4.52337)]"
check "ffn: rms of x at that NS = sqrt(1 - b/c^2)" test "$(json_value "$work/ffn_amp.json" "abs(j['events'][0]['rms'][0] - $rms_exact) < 1e-7")" = True
# The forcing's period must not move along a branch; switching, curves and equilibria are for
# autonomous systems: each refused before any work (exit 2), saying why.
"$bin" continue "$ffn" --param beta --from 10 --to 11 > /dev/null 2> "$work/ffn_beta.err"
check "ffn: continuing beta (the forcing's period moves) exits 2" test $? -eq 2
check "... saying so" grep -qF -- "--param beta: the forcing's period depends on it" "$work/ffn_beta.err"
"$bin" equilibria "$ffn" --param a --from 0 --to 1 > /dev/null 2> "$work/ffn_eq.err"
check "ffn: equilibria of a forced system exit 2" test $? -eq 2
check "... saying why" grep -qF "ffn.toml: its equations use t (a periodically forced system); equilibria is for autonomous systems" "$work/ffn_eq.err"
"$bin" curve "$ffn" --param a --from 0 --to 1 --event NS1 --second amp --second-from 0 --second-to 1 > /dev/null 2> "$work/ffn_curve.err"
check "ffn: curve on a forced system exits 2" test $? -eq 2
check "... saying why" grep -qF "curve (two-parameter curves) is for autonomous systems" "$work/ffn_curve.err"
# No orbit where there is none (issue 32): at the Hopf point (mu = 0) the motion decays as
# r' = -r^3; it was reported a converged, stable orbit of amplitude 6.7e-4. Now exit 4, what
# failed, and no period, multipliers or stability printed.
"$bin" orbit "$src/cases/examples/hopf.toml" --set mu=0 > "$work/hopf0.out" 2>&1
check "orbit at the Hopf point (mu = 0) exits 4" test $? -eq 4
check "... saying there is no orbit" grep -q "no orbit: the motion decays to the equilibrium" "$work/hopf0.out"
check "... and prints no period" test "$(grep -c '^  period\|^  stability\|^  multipliers' "$work/hopf0.out")" -eq 0
# A signal during an equation system's compile (issue 32: the first Ctrl-C exited 130 and left
# the compiler running and its temporaries in the cache): the compiler is stopped, nothing but the
# generated source is left, exit 6. A system of its own (its key not in the cache), the signal
# 0.5 s into its 2-3 s compile (loading takes milliseconds; the handlers are set before the
# compiler starts).
sed 's/mu\*x - w\*y/mu*x - w*y + 0*y/' "$src/cases/examples/hopf.toml" > "$work/signal.toml"
mkdir -p -m 700 "$work/signal_cache"
SYMPATHY_CACHE_DIR="$work/signal_cache" interrupted_after 0.5 "$bin" orbit "$work/signal.toml" \
  > "$work/signal.out" 2>&1
check "SIGINT during a compile exits 6" test $? -eq 6
check "... saying the compile was stopped" grep -q "was stopped by a signal; nothing of it is kept" "$work/signal.out"
check "... leaving only the generated source in the cache" test "$(ls "$work/signal_cache" | grep -vc '\.cpp$')" -eq 0
"$bin" orbit "$src/cases/examples/abc.toml" --start x > /dev/null 2> "$work/nostarts.err"
check "--start on a file without named starts exits 2" test $? -eq 2
check "... saying its [states] are the start" \
  grep -qF "names no starts (no [starts.NAME] tables): its [states] are the start" "$work/nostarts.err"
exit "$failures"
