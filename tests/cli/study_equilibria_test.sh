#!/usr/bin/env bash
# Branches of equilibria in study files ([[equilibria]]), on systems with exact answers: the
# transcritical normal form's branch point and the branch born there (switch_at = "NAME:BP1" and
# "BP1"), the Hopf normal form's family started at an entry's Hopf point (a branch's switch_at =
# "NAME:HB1"), the events table, CSV and JSON as `equilibria` writes them; bad study files refused
# before any work, each message checked.
# Usage: study_equilibria_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
export SYMPATHY_CACHE_DIR="$work/cache"  # never the user's cache
json() { /usr/bin/python3 -c "import json, math, sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }

# The transcritical normal form x' = p x - x^2 (with a decaying y' = -y): the equilibria x = 0 and
# x = p cross at p = 0, where x = 0 exchanges its stability (unstable for p > 0) with x = p. Both
# branches are exact, so the BP is held to 1e-8 and every born point to x = p, y = 0 to 1e-8.
cat > "$work/transcritical.toml" <<'TOML'
kind = "equations"
name = "transcritical"
[states]
x = 0.0
y = 0.0
[parameters]
p = -0.5
[equations]
x = "p*x - x^2"
y = "-y"
TOML
cat > "$work/tc.toml" <<'TOML'
title = "Transcritical normal form"
case = "transcritical.toml"
parameter = "p"
equilibria_axis = "x"

[[equilibria]]
name = "trivial"
from = -0.5
to = 0.5

[[equilibria]]
name = "born"
from = -0.5
to = 0.5
switch_at = "trivial:BP1"

[[equilibria]]
name = "own"
from = -0.5
to = 0.5
switch_at = "BP1"
TOML
"$bin" study "$work/tc.toml" --out "$work/tc" > "$work/tc.out" 2> "$work/tc.err"
check "a study of equilibria alone exits 0" test $? -eq 0
tc=$work/tc/tc.json
check "the trivial branch's one event is a BP at p = 0 (1e-8)" test "$(json "$tc" "
(lambda e: [x['type'] for x in e['events']] == ['BP'] and abs(e['events'][0]['value']) < 1e-8)(j['equilibria'][0])")" = True
check "... x = 0 stable below it, unstable above (exact)" test "$(json "$tc" "
all((p['unstable'] == 0) == (p['value'] < 0) for p in j['equilibria'][0]['points'] if abs(p['value']) > 1e-6)")" = True
check "the branch born at trivial:BP1: x = p, y = 0 at every point (1e-8), over the whole window" test "$(json "$tc" "
(lambda b: b['name'] == 'born' and len(b['points']) > 10 and
 all(abs(p['state'][0] - p['value']) < 1e-8 and abs(p['state'][1]) < 1e-8 for p in b['points']) and
 min(p['value'] for p in b['points']) == -0.5 and max(p['value'] for p in b['points']) == 0.5)(j['equilibria'][1])")" = True
check "... stable where p > 0 (exact)" test "$(json "$tc" "
all((p['unstable'] == 0) == (p['value'] > 0) for p in j['equilibria'][1]['points'] if abs(p['value']) > 1e-6)")" = True
check "... its start named, the window and the case in its entry (as equilibria --json)" test "$(json "$tc" "
(lambda b: b['start'] == \"the branch point BP1 of the equilibria 'trivial'\" and b['from'] == -0.5 and
 b['to'] == 0.5 and b['kind'] == 'equilibria' and b['csv'] == 'tc-born.csv' and 'error' not in b)(j['equilibria'][1])")" = True
check "switch_at = \"BP1\" (the entry's own run) gives the same branch" test "$(json "$tc" "
[len(e['points']) for e in j['equilibria'][1:]] == [len(j['equilibria'][1]['points'])] * 2 and
max(abs(a['state'][0] - b['state'][0]) for a, b in zip(*[e['points'] for e in j['equilibria'][1:]])) < 1e-12")" = True
check "the study's JSON: no branches, the axis state" test "$(json "$tc" "j['branches'] == [] and j['equilibria_axis'] == 'x'")" = True
check "the born branch's CSV: a row per point, x = p (1e-8)" test "$(/usr/bin/python3 -c "
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
born = json.load(open(sys.argv[2]))['equilibria'][1]
print(len(rows) == len(born['points']) and all(abs(float(r['x']) - float(r['p'])) < 1e-8 for r in rows))" "$work/tc/tc-born.csv" "$tc")" = True
check "the events table printed as equilibria prints it" grep -qE '^  BP   -?[0-9.e-]+ +[0-9.e+-]+ +[-+0-9.e]+i' "$work/tc.out"
check "... under the entry's name" grep -q '^bifurcations on equilibria trivial:$' "$work/tc.out"
check "a line per entry" grep -q '^  equilibria born .* points in .* s; ' "$work/tc.out"
"$bin" equilibria "$work/transcritical.toml" --param p --from -0.5 --to 0.5 --json "$work/tc_eq.json" --quiet > "$work/tc_eq.out"
check "... the same table as sympathy equilibria's" test "$(grep -A2 '^bifurcations:' "$work/tc_eq.out" | tail -2)" = \
  "$(grep -A2 '^bifurcations on equilibria trivial:' "$work/tc.out" | tail -2)"

# The Hopf normal form with w = 2: the origin's Hopf point at mu = 0 with omega = 2, and the family
# born there (a [[branches]] entry with switch_at = "NAME:HB1"): circles of period 2 pi / w = pi
# (1e-6 relative) and radius sqrt(mu) (1e-6 where mu > 1e-3).
cat > "$work/hopf2.toml" <<'TOML'
kind = "equations"
name = "hopf2"
[states]
x = 0.0
y = 0.0
[parameters]
mu = -0.5
w = 2.0
[intermediates]
r2 = "x^2 + y^2"
[equations]
x = "mu*x - w*y - x*r2"
y = "w*x + mu*y - y*r2"
TOML
cat > "$work/hb.toml" <<'TOML'
case = "hopf2.toml"
parameter = "mu"

[[branches]]
name = "cycles"
from = 0.0
to = 0.5
switch_at = "origin:HB1"

[[equilibria]]
name = "origin"
from = -0.5
to = 0.5
TOML
"$bin" study "$work/hb.toml" --out "$work/hb" > "$work/hb.out" 2> "$work/hb.err"
check "a study whose branch starts at an equilibria entry's HB1 exits 0" test $? -eq 0
check "the origin's Hopf point at mu = 0 (1e-8), omega = 2, period pi (1e-10)" test "$(json "$work/hb/hb.json" "
(lambda e: [x['type'] for x in e['events']] == ['HB'] and abs(e['events'][0]['value']) < 1e-8 and
 abs(e['events'][0]['hopf']['period'] - math.pi) < 1e-10)(j['equilibria'][0])")" = True
check "the family born there: period pi (1e-6 relative), radius sqrt(mu) (1e-6)" test "$(json "$work/hb/hb.json" "
(lambda b: len(b['points']) > 5 and all(abs(p['period'] - math.pi) < 1e-6 * math.pi for p in b['points']) and
 all(abs(math.hypot(*p['state0']) - math.sqrt(p['value'])) < 1e-6 for p in b['points'] if p['value'] > 1e-3) and
 max(p['value'] for p in b['points']) == 0.5)(j['branches'][0])")" = True
check "both tables printed" test "$(grep -c '^bifurcations on ' "$work/hb.out")" -eq 2

# Bad study files: refused before any work (exit 2), file, line and key named.
bad() {  # bad NAME DESCRIPTION EXPECTED-TEXT: runs $work/NAME.toml, checks exit 2 and the message
  "$bin" study "$work/$1.toml" --out "$work/bad" > /dev/null 2> "$work/$1.err"
  local code=$?
  check "$2: exit 2" test $code -eq 2
  check "... $2: message" grep -qF -- "$3" "$work/$1.err"
  check "... $2: nothing computed" test ! -e "$work/bad/$1.json"
}
head_tc() { printf 'case = "transcritical.toml"\nparameter = "p"\n'; }
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\ncolour = 1\n'; } > "$work/b_key.toml"
bad b_key "an unknown key" "b_key.toml:7: key 'equilibria[1].colour'"
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = "low"\nto = 0.5\n'; } > "$work/b_type.toml"
bad b_type "a wrong type" "b_type.toml:5: key 'equilibria[1].from': expected a number, got \"low\""
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\n'; } > "$work/b_to.toml"
bad b_to "a missing to" "b_to.toml:3: key 'equilibria[1].to' is missing"
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\nswitch_at = "HB1"\n'; } > "$work/b_hb.toml"
bad b_hb "switch_at HB1 in an equilibria entry" "b_hb.toml:7: key 'equilibria[1].switch_at' HB1: expected a branch point of the equilibria, BP followed by its number along them (BP1, or NAME:BP1): only there is a branch of equilibria born (the orbits born at a Hopf point: a [[branches]] entry with switch_at = \"NAME:HB1\")"
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\nswitch_at = "b:BP1"\n[[equilibria]]\nname = "b"\nfrom = -0.5\nto = 0.5\n'; } > "$work/b_later.toml"
bad b_later "switch_at naming an entry listed after" "b_later.toml:7: key 'equilibria[1].switch_at': expected a branch point of this entry's equilibria (BP1) or of an [[equilibria]] entry listed before it (NAME:BP1); 'b' is not one"
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\n[[branches]]\nname = "a"\nfrom = 0.0\nto = 0.5\n'; } > "$work/b_twice.toml"
bad b_twice "a name used by a branch and an equilibria entry" "b_twice.toml:8: key 'branches[1].name': expected a name no other branch or equilibria entry has (it names files), got \"a\""
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\n[[equilibria]]\nname = "b"\nfrom = -0.5\nto = 0.5\nat = 0.1\nswitch_at = "a:BP1"\n'; } > "$work/b_at.toml"
bad b_at "at beside switch_at" "b_at.toml:11: key 'equilibria[2].at': expected no at beside switch_at"
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\n[[equilibria]]\nname = "b"\nfrom = -0.5\nto = 0.5\nset = { p = 0.1 }\nswitch_at = "a:BP1"\n'; } > "$work/b_set.toml"
bad b_set "set beside NAME:BP1" "b_set.toml:11: key 'equilibria[2].set': expected no set beside switch_at = \"a:BP1\" (the branch starts at that branch point, at a's parameter values)"
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\n[[branches]]\nname = "b"\nfrom = 0.0\nto = 0.5\nswitch_at = "a:BP1"\n'; } > "$work/b_branch_bp.toml"
bad b_branch_bp "a periodic branch at an equilibria entry's BP" "b_branch_bp.toml:11: key 'branches[1].switch_at': expected a Hopf point of the equilibria 'a' (a:HB1): only there are orbits born"
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\n[[branches]]\nname = "b"\nfrom = 0.0\nto = 0.5\nswitch_at = "a:HB1"\nequilibria = "eq.json"\n'; } > "$work/b_file.toml"
bad b_file "NAME:HB1 beside saved equilibria" "b_file.toml:12: key 'branches[1].equilibria': expected no equilibria beside switch_at = \"a:HB1\""
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\nuser_points = [0.7]\n'; } > "$work/b_uz.toml"
bad b_uz "a user point outside the window" "b_uz.toml:7: key 'equilibria[1].user_points': expected values between from and to (the branch never reaches 0.7), got 0.7"
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\nstep = -1\n'; } > "$work/b_step.toml"
bad b_step "a negative step (the engine's validation)" "b_step.toml:3: equilibria[1].step: expected"
{ head_tc; printf '[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\nparent = "x.json"\nfrom_point = "UZ1"\nswitch_at = "BP1"\n'; } > "$work/b_saved.toml"
bad b_saved "from_point beside switch_at" "b_saved.toml:8: key 'equilibria[1].from_point': expected no switch_at beside it"
{ head_tc; printf 'equilibria_axis = "z"\n[[equilibria]]\nname = "a"\nfrom = -0.5\nto = 0.5\n'; } > "$work/b_axis.toml"
bad b_axis "an equilibria_axis that is no state" "b_axis.toml: equilibria_axis 'z' is not a state of"
{ head_tc; printf 'title = "nothing"\n'; } > "$work/b_none.toml"
bad b_none "neither branches nor equilibria" "b_none.toml: key 'branches' is missing; expected [[branches]] tables, [[equilibria]] tables or both"
{ head_tc; printf '[[equilibria]]\nname = "a-events"\nfrom = -0.5\nto = 0.5\n[[branches]]\nname = "a"\nfrom = 0.0\nto = 0.5\n'; } > "$work/b_clash.toml"
bad b_clash "an entry's CSV that is a branch's events CSV" "the same file as branch 'a''s events CSV"
printf 'case = "%s"\nparameter = "k"\n[[equilibria]]\nname = "a"\nfrom = 10.0\nto = 20.0\n' "$src/cases/row2.toml" > "$work/b_start.toml"
bad b_start "a metronome case's entry without start" "b_start.toml: equilibria 'a': key 'start' is missing; expected the name of one of"

exit "$failures"
