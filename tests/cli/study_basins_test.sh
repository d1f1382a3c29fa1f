#!/usr/bin/env bash
# Basin shares walked along a study's parameter ([basins] in a study file), on the pitchfork of
# cycles (cases/examples/cycle_pitchfork_study.toml), whose every fate is known in closed form:
# the circle w = 0 wins every start before mu = 0, the circles w = +-sqrt(mu) born at its BP win
# them all after (each the starts with w of its sign); the attractors named by the study's
# branches, their orbits exact to 1e-8, the share changes placed at the located BP; the CSV and
# the JSON; the row setup's walk, each change at its located event; bad [basins] tables refused
# before any work, each message checked; the walk's journal and its resume. About 17 s.
# With MPIRUN (built with MPI), the row setup's walk under mpirun with 2 and 3 ranks gives the
# files of the walk on threads, and resumes from a journal cut short (about 15 s more).
# Usage: study_basins_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR [MPIRUN]
set -u
bin=$1 src=$2 work=$3 mpirun=${4:-}
rm -rf "$work"
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
export SYMPATHY_CACHE_DIR="$work/cache"  # never the user's cache
json() { /usr/bin/python3 -c "import json, math, sys; j=json.load(open(sys.argv[1]))['basins']; print($2)" "$1"; }

study=$src/cases/examples/cycle_pitchfork_study.toml
"$bin" study "$study" --out "$work/cp" > "$work/cp.out" 2> "$work/cp.err"
check "the walk exits 0" test $? -eq 0
j=$work/cp/cycle_pitchfork_study.json
check "six values, -0.25 to 0.25" test "$(json "$j" "
len(j['values']) == 6 and all(abs(a - b) < 1e-15 for a, b in zip(j['values'], [-0.25, -0.15, -0.05, 0.05, 0.15, 0.25]))")" = True
check "the circle wins every start before mu = 0, none after" test "$(json "$j" "
[s for s in j['shares'] if s['name'] == 'circle'][0]['share'] == [1, 1, 1, 0, 0, 0]")" = True
check "the pair's two shares: 0 before, together 1 after" test "$(json "$j" "
(lambda p: len(p) == 2 and all(a + b == (1 if v > 0 else 0) for v, a, b in zip(j['values'], p[0]['share'], p[1]['share'])))([s for s in j['shares'] if s['branch'] == 'pair'])")" = True
check "the pair's orbits are w = +-sqrt(mu), period 2 pi (1e-8)" test "$(json "$j" "
all(abs(abs(a['state'][2]) - math.sqrt(v)) < 1e-8 and abs(a['period'] - 2 * math.pi) < 1e-8 for v, l in zip(j['values'], j['attractors']) for a in l if a['branch'] == 'pair')")" = True
check "... of opposite signs at every value after the BP" test "$(json "$j" "
all(sum(a['state'][2] for a in l if a['branch'] == 'pair') == 0 or abs(sum(a['state'][2] for a in l if a['branch'] == 'pair')) < 1e-8 for l in j['attractors'][3:])")" = True
check "every run certified" test "$(json "$j" "all(f['certified'] == 20 for f in j['fates'])")" = True
check "three changes between -0.05 and 0.05, each at the circle's BP (|mu| < 1e-8)" test "$(json "$j" "
len(j['changes']) == 3 and all(abs(c['before'] + 0.05) < 1e-15 and abs(c['after'] - 0.05) < 1e-15 and len(c['events']) == 1 and c['events'][0]['type'] == 'BP' and abs(c['events'][0]['parameter']) < 1e-8 for c in j['changes'])")" = True
check "the shares' CSV: 18 rows, the circle's at mu = 0.05 zero" test "$(/usr/bin/python3 -c "
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print(len(rows) == 18 and [r['count'] for r in rows if r['attractor'] == 'circle' and r['value'] == '0.05'] == ['0'])" "$work/cp/cycle_pitchfork_study-basins.csv")" = True
check "the table names the change and its BP" grep -qE "^  pair \(1\) appears between mu = -0.05 and 0.05: BP of circle at" "$work/cp.out"

# The row setup at Table II (cases/figures/basins_walk_k.toml, about 5 s): every appearance and
# disappearance of a share lies at the located event where stability changes, as continuation
# places it: the branch born at the anti-phase BP appears beyond its NS point (41.62 N/m) and is
# gone beyond the BP (47.07); the torus appears beyond the anti-phase NS point 49.69 and is gone
# beyond 56.11, where the anti-phase orbit wins; runs on the torus have one rotation number per
# value (to 1e-3). The same files with one thread as with two.
walk=$src/cases/figures/basins_walk_k.toml
"$bin" study "$walk" --out "$work/walk" > "$work/walk.out" 2> "$work/walk.err"
check "the row setup's walk exits 0" test $? -eq 0
w=$work/walk/basins_walk_k.json
event_of() {  # event_of NAME APPEARS TYPE VALUE: the change of NAME has an event TYPE within 0.01 of VALUE
  test "$(json "$w" "any(c['name'].startswith('$1') and c['appears'] == $2 and any(e['type'] == '$3' and abs(e['parameter'] - $4) < 0.01 for e in c['events']) for c in j['changes'])")" = True
}
check "born-at-bp appears at its NS point (41.62)" event_of born-at-bp True NS 41.6228
check "born-at-bp disappears at the anti-phase BP (47.07)" event_of born-at-bp False BP 47.0656
check "the torus appears at the anti-phase NS point 49.69" event_of torus True NS 49.6853
check "the torus disappears at the anti-phase NS point 56.11" event_of torus False NS 56.1116
check "the anti-phase orbit appears at 56.11" event_of anti-phase True NS 56.1116
check "one rotation number per value on the torus (1e-3)" test "$(json "$w" "
all(max(r) - min(r) < 1e-3 for r in ([x['rotation_number'] for x in runs if x['fate'] == 'torus'] for runs in j['runs']) if r)")" = True
sed 's/^box = /threads = 1\nbox = /' "$walk" | sed "s#case = \"../row2.toml\"#case = \"$src/cases/row2.toml\"#" > "$work/walk1.toml"
"$bin" study "$work/walk1.toml" --out "$work/walk1" > /dev/null 2>&1
check "one thread: the same shares" cmp "$work/walk/basins_walk_k-basins.csv" "$work/walk1/walk1-basins.csv"

# The walk's journal: each run's fate as it finishes (OUT/NAME-basins-journal.csv, with the
# study's record beside it). A walk cut short (its first 23 runs kept, the 24th half written, as a
# kill leaves it) and resumed gives the files of the walk that was not: the same shares CSV, the
# same JSON walk; without --resume the journal in the way is refused, and with a study changed
# (another seed) the resume is.
check "the walk's journal has every run" test "$(($(wc -l < "$work/walk/basins_walk_k-basins-journal.csv") - 1))" -eq 50
mkdir -p "$work/cut"
cp "$work/walk/basins_walk_k-basins-journal.csv.study" "$work/cut/"
{ head -n 24 "$work/walk/basins_walk_k-basins-journal.csv"; sed -n 25p "$work/walk/basins_walk_k-basins-journal.csv" | head -c 12; } > "$work/cut/basins_walk_k-basins-journal.csv"
"$bin" study "$walk" --out "$work/cut" > "$work/cut.out" 2> "$work/cut.err"
check "a journal in the way without --resume: exit 2" test $? -eq 2
check "... naming it and --resume" grep -q "basins-journal.csv is the journal of an earlier walk; expected --resume" "$work/cut.err"
"$bin" study "$walk" --out "$work/cut" --resume > "$work/cut.out" 2> "$work/cut.err"
check "the walk resumed exits 0" test $? -eq 0
check "... its shares those of the walk not cut short" cmp "$work/walk/basins_walk_k-basins.csv" "$work/cut/basins_walk_k-basins.csv"
check "... and its JSON walk" test "$(/usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f))['basins'] for f in sys.argv[1:])
print(a == b)" "$work/walk/basins_walk_k.json" "$work/cut/basins_walk_k.json")" = True
sed 's/^starts = 10 /seed = 2\nstarts = 10 /' "$walk" | sed "s#case = \"../row2.toml\"#case = \"$src/cases/row2.toml\"#" > "$work/cut/basins_walk_k.toml"
"$bin" study "$work/cut/basins_walk_k.toml" --out "$work/cut" --resume > /dev/null 2> "$work/cut.err"
check "a resume by another study: exit 2" test $? -eq 2
check "... naming the difference" grep -q "basins-journal.csv" "$work/cut.err"
"$bin" study "$study" --out "$work/cp" --resume > /dev/null 2> "$work/cut.err"
check "--resume of a walk whose journal is complete exits 0" test $? -eq 0

# Under mpirun: rank 0 computes the study and writes its files, the others compute the branches
# again and share the walk's runs; the files are those of the walk on threads. A study without
# [basins] is refused (each rank would compute it whole). As root in a container: the flags.
if [ -n "$mpirun" ]; then
  same_walk() {  # same_walk DIR: DIR's shares CSV and JSON walk are the threads' walk's
    cmp -s "$work/walk/basins_walk_k-basins.csv" "$1/basins_walk_k-basins.csv" &&
      test "$(/usr/bin/python3 -c "
import json, sys
a, b = (json.load(open(f))['basins'] for f in sys.argv[1:])
print(a == b)" "$work/walk/basins_walk_k.json" "$1/basins_walk_k.json")" = True
  }
  for np in 2 3; do
    "$mpirun" --allow-run-as-root --oversubscribe -np $np "$bin" study "$walk" --out "$work/mpi$np" \
      > "$work/mpi$np.out" 2> "$work/mpi$np.err"
    check "the walk under mpirun -np $np exits 0" test $? -eq 0
    check "... its files those of the walk on threads" same_walk "$work/mpi$np"
  done
  check "... one report (rank 0's)" test "$(grep -c "^basins along" "$work/mpi3.out")" -eq 1
  mkdir -p "$work/mpicut"
  cp "$work/walk/basins_walk_k-basins-journal.csv.study" "$work/mpicut/"
  head -n 24 "$work/walk/basins_walk_k-basins-journal.csv" > "$work/mpicut/basins_walk_k-basins-journal.csv"
  "$mpirun" --allow-run-as-root --oversubscribe -np 3 "$bin" study "$walk" --out "$work/mpicut" \
    --resume > /dev/null 2> "$work/mpicut.err"
  check "a walk cut short resumed under mpirun -np 3 exits 0" test $? -eq 0
  check "... its files those of the walk on threads" same_walk "$work/mpicut"
  "$mpirun" --allow-run-as-root --oversubscribe -np 2 "$bin" study "$src/cases/figures/fig08.toml" \
    --out "$work/mpif8" > /dev/null 2> "$work/mpif8.err"
  check "a study without [basins] under mpirun: exit 2" test $? -eq 2
  check "... saying why" grep -q "fig08.toml has no \[basins\]: the ranks share a walk's runs" "$work/mpif8.err"
fi

# Bad [basins] tables: refused before any work (exit 2), file, line and key named.
head -n 19 "$study" | sed "s#case = \"cycle_pitchfork.toml\"#case = \"$src/cases/examples/cycle_pitchfork.toml\"#" > "$work/head.toml"
basins() {  # basins NAME LINES...: a study file with the branches and a [basins] table of LINES
  local name=$1
  shift
  { cat "$work/head.toml"; printf '[basins]\n'; printf '%s\n' "$@"; } > "$work/$name.toml"
}
bad() {  # bad NAME DESCRIPTION EXPECTED-TEXT
  "$bin" study "$work/$1.toml" --out "$work/bad" > /dev/null 2> "$work/$1.err"
  local code=$?
  check "$2: exit 2" test $code -eq 2
  check "... $2: message" grep -qF -- "$3" "$work/$1.err"
  check "... $2: nothing computed" test ! -e "$work/bad/$1.json"
}
basins b_key 'from = -0.2' 'to = 0.2' 'count = 3' 'box = { w = [-1, 1] }' 'colour = 1'
bad b_key "an unknown key" "b_key.toml:25: key 'basins.colour'"
basins b_box 'from = -0.2' 'to = 0.2' 'count = 3'
bad b_box "no box" "key 'basins.box' is missing"
basins b_state 'from = -0.2' 'to = 0.2' 'count = 3' 'box = { z = [-1, 1] }'
bad b_state "a box state the case lacks" "b_state.toml:24: key 'basins.box.z': not a state of"
basins b_range 'from = -0.2' 'to = 0.2' 'count = 3' 'box = { w = [1, -1] }'
bad b_range "a reversed range" "b_range.toml:24: key 'basins.box.w': expected [LOWER, UPPER] with LOWER <= UPPER"
basins b_count 'from = -0.2' 'to = 0.2' 'count = 0' 'box = { w = [-1, 1] }'
bad b_count "no values" "b_count.toml:23: key 'basins.count': expected an integer from 1 to 10000"
basins b_t 'from = -0.2' 'to = 0.2' 'count = 3' 't_end = -1.0' 'box = { w = [-1, 1] }'
bad b_t "a negative t_end" "b_t.toml:24: key 'basins.t_end': expected a positive number"
basins b_dt 'from = -0.2' 'to = 0.2' 'count = 3' 'dt = 500.0' 'box = { w = [-1, 1] }'
bad b_dt "a dt beyond t_end" "b_dt.toml:24: key 'basins.dt': expected a positive number up to t_end"
{ cat "$work/head.toml" | sed '/^\[\[branches\]\]/,$d'; printf '[[equilibria]]\nname = "e"\nfrom = -0.2\nto = 0.2\n[basins]\nfrom = -0.2\nto = 0.2\ncount = 3\nbox = { w = [-1, 1] }\n'; } > "$work/b_alone.toml"
bad b_alone "basins without branches" "[basins] only beside [[branches]] tables"
exit $failures
