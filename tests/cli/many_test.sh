#!/usr/bin/env bash
# Many metronomes on one 2-D platform (cases/many, spread directions, every fourth detuned): the
# splay orbit, its multipliers and its accuracy, or a failure that says why.
# Usage: many_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR N [RTOL [TRANSIENT]]
set -u
bin=$1 src=$2 work=$3 n=$4 rtol=${5:-1e-9} transient=${6:-20}
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
atol=$(/usr/bin/python3 -c "print($rtol * 1e-2)")
# BDF with the forward-sensitivity module (the structured linear solver above 3 metronomes), pinned:
# the error bounds below are BDF's at the given rtol (the default accuracy preset is Adams on the
# augmented system, whose trivial error runs 2-3x higher per rtol here: 1.9e-6 at 1e-9 on many32).
"$bin" orbit "$src/cases/many/many$n.toml" --start splay --transient "$transient" --rtol "$rtol" \
  --atol "$atol" --method bdf --sensitivities forward --json "$work/orbit$n.json" 2> "$work/orbit$n.err"
code=$?
grep -v '^    [0-9]' "$work/orbit$n.err"
check "many$n: the orbit converges (exit 0)" test $code -eq 0
# Expected values: the Newton tolerance is 20 rtol and the trivial multiplier's error about
# 200-500 rtol (NUMERICS.md; 250 rtol measured on many16 and many64): below 1000 rtol. The case turns into itself when rotated by
# 4 metronomes (180 * 4 / n degrees, same detuning pattern) and the platform is isotropic, so
# metronome 1 + 4 j repeats metronome 1's swing delayed by j 4 / n half periods: its phase
# to th1 is -4 pi j / n exactly, and its amplitude is th1's.
/usr/bin/python3 - "$work/orbit$n.json" "$n" "$rtol" <<'PY'
import json, math, sys
d = json.load(open(sys.argv[1])); n = int(sys.argv[2]); rtol = float(sys.argv[3])
bad = []
if not d["converged"]: bad.append("not converged: " + d["newton"]["reason"])
# Newton's own tolerance: 20 rtol times the state's size (attainable_tolerance, periodic_orbit.hpp;
# the velocities reach 8 rad/s here).
size = max(1.0, max(abs(v) for v in d["state0"]))
if not d["residual"] < 20 * rtol * size: bad.append("residual %g above %g" % (d["residual"], 20 * rtol * size))
if not d["trivial_multiplier_error"] < 1000 * rtol: bad.append("trivial error %g" % d["trivial_multiplier_error"])
if d["stability"] != "stable": bad.append("stability " + d["stability"])
names = d["state_names"]; amp = d["amplitudes"]
a1 = amp["th1"] if isinstance(amp, dict) else amp[names.index("th1")]
for j in range(1, n // 4):
    i = 1 + 4 * j
    want = math.remainder(-4.0 * math.pi * j / n, 2.0 * math.pi)
    got = d["phase_differences"][i - 2] if isinstance(d["phase_differences"], list) else d["phase_differences"]["th%d" % i]
    if abs(math.remainder(got - want, 2.0 * math.pi)) > 1e-4: bad.append("th%d phase %g, expected %g" % (i, got, want))
    ai = amp["th%d" % i] if isinstance(amp, dict) else amp[names.index("th%d" % i)]
    if abs(ai - a1) > 1e-6: bad.append("th%d amplitude %g, th1 %g" % (i, ai, a1))
print("\n".join(bad) if bad else "all checks passed")
sys.exit(1 if bad else 0)
PY
check "many$n: accuracy, stability and the rotational symmetry's phases and amplitudes" test $? -eq 0
exit $failures
