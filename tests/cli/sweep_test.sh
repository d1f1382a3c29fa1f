#!/usr/bin/env bash
# The sweep command end to end on lcbp (cases/examples/lcbp.toml): the circles r = p1 and r = p2
# exchange stability at the branch point p1 = p2 exactly, so a branch in p1 at each p2 of the
# grid has its BP at p1 = p2 (to 1e-9 and within its reported uncertainty: located on the
# regular branch-point system, measured 1e-12 to 4e-11 off). Identical files whatever the threads and under mpirun; a resumed journal
# completes the sweep without recomputing; bad input refused before any work. About 3 s.
# Usage: sweep_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR [MPIRUN]
set -u
bin=$1 src=$2 work=$3 mpirun=${4:-}
rm -rf "$work"
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
. "$(dirname "$0")/damped_oscillator.sh"
export SYMPATHY_CACHE_DIR="$work/cache"  # never the user's cache
lcbp=$src/cases/examples/lcbp.toml
run=("$bin" sweep "$lcbp" --param p1 --from 1 --to 3 --over p2=1.5:2.5:3)

"${run[@]}" --threads 1 --out "$work/one" > "$work/one.out" 2> "$work/one.err"
check "sweep exits 0" test $? -eq 0
check "one BP per branch, at p1 = p2 (1e-9, within its uncertainty)" test "$(/usr/bin/python3 -c "
import json, sys
j = json.load(open(sys.argv[1]))
print(j['complete'] and [b['value'] for b in j['branches']] == [1.5, 2.0, 2.5] and
      all([e['type'] for e in b['events']] == ['BP'] and abs(b['events'][0]['value'] - b['value']) < 1e-9 and
          abs(b['events'][0]['value'] - b['value']) <= b['events'][0]['uncertainty']
          for b in j['branches']))" "$work/one/sweep.json")" = True
check "events CSV: a row per event, in task order" test "$(cut -d, -f1,2 "$work/one/sweep_events.csv" | tr '\n' ' ')" = "p2,type 1.5,BP 2,BP 2.5,BP "
check "prints the run time" grep -q 'run time' "$work/one.err"

"${run[@]}" --threads 2 --out "$work/two" > /dev/null 2>&1
# (The journal's rows are in the order tasks finished, which the threads decide; the final files
# are in task order.)
for f in sweep_events.csv sweep.json; do
  check "$f identical with 1 and 2 threads" cmp -s "$work/one/$f" "$work/two/$f"
done
if [ -n "$mpirun" ]; then
  "$mpirun" --allow-run-as-root --oversubscribe -np 3 "${run[@]}" --out "$work/mpi" 2> "$work/mpi.err"
  check "mpirun -np 3 exits 0" test $? -eq 0
  for f in sweep_events.csv sweep.json; do
    check "$f identical with mpirun -np 3 and 1 thread" cmp -s "$work/one/$f" "$work/mpi/$f"
  done
fi

# A run killed after its first branch: its journal holds that row alone. Resumed, the sweep
# computes the other two and writes the files of an uninterrupted run.
mkdir -p "$work/resumed"
head -2 "$work/one/sweep_journal.csv" > "$work/resumed/sweep_journal.csv"
cp "$work/one/sweep_journal.csv.study" "$work/resumed/"  # the study's record, beside it
"${run[@]}" --out "$work/resumed" --resume > /dev/null 2> "$work/resumed.err"
check "resume exits 0" test $? -eq 0
check "resume computes only the missing branches" grep -q '1 in the journal, 2 to compute' "$work/resumed.err"
for f in sweep_events.csv sweep.json; do
  check "$f of the resumed run identical" cmp -s "$work/one/$f" "$work/resumed/$f"
done

# Without --param, an orbit at each value: lcbp at p2 = 2 from (2.5, 0), outside r = 2, falls on
# the stable circle, r = 2 while p1 < 2 (radial multiplier exp(-2 (2 - p1))), r = p1 beyond
# (exp(-p1 (p1 - 2))); period 1 each. To 1e-8.
"$bin" sweep "$lcbp" --initial x=2.5 --over p1=1.25:2.75:4 --out "$work/orbits" > /dev/null 2> "$work/orbits.err"
check "a sweep of orbits exits 0" test $? -eq 0
check "... each orbit the stable circle's, exactly" test "$(/usr/bin/python3 -c "
import json, math, sys
j = json.load(open(sys.argv[1]))
ok = [o['value'] for o in j['orbits']] == [1.25, 1.75, 2.25, 2.75]
for o in j['orbits']:
    p1 = o['value']
    mu = math.exp(-2 * (2 - p1)) if p1 < 2 else math.exp(-p1 * (p1 - 2))
    ok = ok and o['converged'] and abs(o['period'] - 1) < 1e-8
    ok = ok and abs(o['max_modulus'] - mu) < 1e-8
print(ok)" "$work/orbits/sweep.json")" = True
check "... and its table" test "$(head -1 "$work/orbits/sweep_orbits.csv")" = "p1,converged,period,stability,max_modulus,trivial_error,residual"

# With --data, a fit at each value: the profile of a fit in the swept parameter. The damped
# oscillator x'' + 2 zeta w x' + w^2 x = 0 (exact samples of exp(-zeta w t) cos(w_d t) at w = 1,
# zeta = 0.05), w fitted at zeta = 0.04, 0.05, 0.06: the residual least at the true zeta, where w
# is 1 to 1e-6.
write_damped_oscillator "$work"
"$bin" sweep "$work/oscillator.toml" --over zeta=0.04:0.06:3 --data "$work/oscillator.csv" --free w \
  --out "$work/fits" > /dev/null 2> "$work/fits.err"
check "a sweep of fits exits 0" test $? -eq 0
check "... least residual at the true zeta, w = 1 there" test "$(/usr/bin/python3 -c "
import json, sys
f = json.load(open(sys.argv[1]))['fits']
rss = [x['rss'] for x in f]
print(all(x['converged'] for x in f) and rss[1] < rss[0] and rss[1] < rss[2] and
      abs(f[1]['values']['w'] - 1) < 1e-6)" "$work/fits/sweep.json")" = True
"$bin" sweep "$work/oscillator.toml" --over zeta=0.04:0.06:3 --data "$work/oscillator.csv" \
  --free zeta --out "$work/bad" > /dev/null 2> "$work/free_swept.err"
check "fitting the swept parameter: exit 2" test $? -eq 2
check "... saying so" grep -qF -- "--free zeta: the swept parameter (--over)" "$work/free_swept.err"

# Bad input: exit 2 before any work.
bad() {  # bad NAME EXPECTED-MESSAGE ARGS...
  local name=$1 expected=$2; shift 2
  "$bin" sweep "$lcbp" "$@" > /dev/null 2> "$work/$name.err"
  check "$name: exit 2" test $? -eq 2
  check "$name: message" grep -qF -- "$expected" "$work/$name.err"
}
bad same_parameter "--over p1: expected a parameter other than --param" \
  --param p1 --from 1 --to 3 --over p1=1:2:3 --out "$work/bad"
bad empty_grid "an empty grid; expected COUNT >= 1" --param p1 --from 1 --to 3 --over p2=1:2:0 --out "$work/bad"
bad unknown "--over q: not a parameter of $lcbp" --param p1 --from 1 --to 3 --over q=1:2:3 --out "$work/bad"
bad malformed "--over p2=1:2: expected NAME=FROM:TO:COUNT" --param p1 --from 1 --to 3 --over p2=1:2 --out "$work/bad"
bad journal_exists "is the journal of an earlier run; expected --resume" \
  --param p1 --from 1 --to 3 --over p2=1.5:2.5:3 --out "$work/one"
bad journal_other_range "a journal of another study: option --to was 3 when the journal was started, now 2.8" \
  --param p1 --from 1 --to 2.8 --over p2=1.5:2.5:3 --out "$work/one" --resume
mkdir -p "$work/norecord"
head -2 "$work/one/sweep_journal.csv" > "$work/norecord/sweep_journal.csv"
bad journal_without_record "no record of the study it belongs to" \
  --param p1 --from 1 --to 3 --over p2=1.5:2.5:3 --out "$work/norecord" --resume
bad fit_with_param "--data: a fit at each value, given with --param" \
  --param p1 --from 1 --to 3 --over p2=1:2:3 --data "$work/oscillator.csv" --out "$work/bad"
bad branch_option_without_param "--from: a branch's option, given without --param" \
  --from 1 --over p2=1:2:3 --out "$work/bad"
check "no file written for bad input" test ! -e "$work/bad"
exit "$failures"
