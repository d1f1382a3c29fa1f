#!/usr/bin/env bash
# Nothing lost, nothing wrong (the reliability issue): failed writes are errors, outputs never
# replace an input or each other, signals stop a run with complete files, parameter ranges are
# checked against the model's domain, all before any work where they can be.
# Usage: outputs_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
json() { /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }
row2="$src/cases/row2.toml"
export SYMPATHY_CACHE_DIR="$work/cache"  # never the user's cache

# A full disk: /dev/full refuses every write with ENOSPC (exit 5, the path and the reason named).
if [ -e /dev/full ]; then
  "$bin" orbit "$row2" --start anti-phase --json /dev/full > /dev/null 2> "$work/full.err"
  check "orbit --json /dev/full exits 5" test $? -eq 5
  check "the message names the path and the reason" grep -q "/dev/full: cannot write (No space left on device)" "$work/full.err"
  check "/dev/full is still a device" test -c /dev/full
  "$bin" simulate "$row2" --start anti-phase --t-end 2 --out /dev/full 2> "$work/full.err"
  check "simulate --out /dev/full exits 5 before any work" test $? -eq 5
  "$bin" continue "$row2" --start anti-phase --param k --from 10 --to 11 --quiet --csv /dev/full > /dev/null 2> "$work/full.err"
  check "continue --csv /dev/full exits 5" test $? -eq 5
fi

# Outputs that collide with an input or with each other, refused before any work (exit 2).
cp "$row2" "$work/case.toml"
"$bin" simulate "$work/case.toml" --start anti-phase --t-end 1 --out "$work/../$(basename "$work")/case.toml" 2> "$work/err"
check "simulate --out CASE exits 2" test $? -eq 2
check "... and says it is the case file" grep -q "is the case file" "$work/err"
check "... and the case file is intact" cmp -s "$row2" "$work/case.toml"
# A hard link to the case file is the case file (issue 32: the check compared resolved paths,
# and the link's name is a path of its own).
rm -f "$work/hard.csv"
ln "$work/case.toml" "$work/hard.csv"
"$bin" simulate "$work/case.toml" --start anti-phase --t-end 1 --out "$work/hard.csv" 2> "$work/err"
check "simulate --out HARD-LINK-TO-CASE exits 2" test $? -eq 2
check "... and says it is the case file" grep -q "hard.csv: is the case file" "$work/err"
check "... and the case file is intact" cmp -s "$row2" "$work/case.toml"
# A recording read by a sweep's fits is an input: a sweep writing its table over it is refused.
mkdir -p "$work/sweep"
"$bin" simulate "$src/cases/examples/hopf.toml" --t-end 10 --dt 0.1 --out "$work/sweep/sweep_fits.csv" 2> /dev/null
cp "$work/sweep/sweep_fits.csv" "$work/recording.csv"
"$bin" sweep "$src/cases/examples/hopf.toml" --data "$work/sweep/sweep_fits.csv" --free w --over mu=0.2:0.3:2 --out "$work/sweep" > /dev/null 2> "$work/err"
check "sweep --data D --out DIR (the table would be D) exits 2" test $? -eq 2
check "... naming the recording" grep -q "is the recording (--data)" "$work/err"
check "... and the recording is intact" cmp -s "$work/recording.csv" "$work/sweep/sweep_fits.csv"
"$bin" continue "$row2" --start anti-phase --param k --from 10 --to 11 --csv "$work/same" --json "$work/same" 2> "$work/err"
check "continue --csv F --json F exits 2" test $? -eq 2
check "... naming both options" grep -q -- "--json $work/same: the same file as --csv" "$work/err"
printf 'case = "%s"\nparameter = "k"\n[[branches]]\nname = "a"\nstart = "anti-phase"\nfrom = 10.0\nto = 11.0\n[[branches]]\nname = "a"\nstart = "in-phase"\nfrom = 10.0\nto = 11.0\n' "$row2" > "$work/twice.toml"
"$bin" study "$work/twice.toml" --out "$work" > /dev/null 2> "$work/err"
check "a study with two branches of one name exits 2" test $? -eq 2
check "... naming the file, line and key" grep -q "twice.toml:9: key 'branches\[2\].name': expected a name no other branch or equilibria entry has" "$work/err"
"$bin" continue "$row2" --start anti-phase --param k --from 10 --to 11 --json "$work/missing/dir.json" 2> "$work/err"
check "an output in a missing directory exits before any work" test $? -eq 5
check "... naming the directory" grep -q "does not exist" "$work/err"

# Parameter ranges outside the model's domain (exit 2, before any work).
"$bin" continue "$row2" --start anti-phase --param M --from -0.5 --to 1 2> "$work/err"
check "--from -0.5 for M exits 2" test $? -eq 2
check "... saying M must be positive" grep -q "M = -0.5 is outside the model's domain: M must be a positive number" "$work/err"

# The impulsive escapement (eq. 2) is piecewise smooth: orbit, continue, curve and map run it (the
# monodromy crosses the switching surfaces with saltation matrices; a branch ends where an orbit
# grazes a surface); equilibria, which lie on its surfaces, refuse it at once (exit 2), naming
# the case file and its escapement.
sed 's/^escapement = "half".*/escapement = "impulsive"/' "$row2" > "$work/impulsive.toml"
"$bin" orbit "$work/impulsive.toml" --start in-phase > "$work/out" 2> "$work/err"
check "orbit on the impulsive escapement runs" test $? -eq 0
"$bin" continue "$work/impulsive.toml" --start in-phase --param d --from 2.4e-6 --to 1e-4 --quiet > "$work/out" 2> "$work/err"
check "continue on the impulsive escapement ends at a grazing (exit 0)" test $? -eq 0
check "... naming it" grep -q "stopped: grazing near d = 1.5679" "$work/out"
# Curves and maps of its orbits run: the anti-phase NS curve in c closes where the smoothed
# model's does (c = 0.2954 N s/m there; docs/guides/curves-and-maps.md), about 2 s; a map of the
# anti-phase orbit on a 4 x 3 grid, about 1.5 s.
"$bin" curve "$work/impulsive.toml" --start anti-phase --param k --from 1 --to 100 --event NS1 \
  --second c --second-from 0 --second-to 0.5 --quiet > "$work/out" 2> "$work/err"
check "curve on the impulsive escapement runs" test $? -eq 0
check "... its NS curve turns back in c at 0.29548" grep -qE "turn in c +53\.09[0-9]+ +0\.29548" "$work/out"
sed "s|\.\./row2.toml|$row2|" "$src/tests/fuzz/corpus/map_file/map_impulsive.toml" > "$work/map_impulsive.toml"
"$bin" map "$work/map_impulsive.toml" --out "$work/map" --quiet > "$work/out" 2> "$work/err"
check "a map file with escapement = \"impulsive\" runs" test $? -eq 0
check "... its BP curve from the hybrid branch's BP" grep -qE "BP +BP at k = 47\.0666015" "$work/out"
{ cat "$work/map_impulsive.toml"; printf '[[equilibria]]\nname = "rest"\n'; } > "$work/map_eq.toml"
"$bin" map "$work/map_eq.toml" --out "$work/map" --quiet > /dev/null 2> "$work/err"
check "a map's [[equilibria]] on the impulsive escapement exits 2" test $? -eq 2
check "... naming the case, its escapement and the equilibria" grep -q "row2.toml: key 'escapement': the impulsive escapement (eq. 2) switches discontinuously, and a map's \[\[equilibria\]\] is not built" "$work/err"
# An equation case file with sign() is piecewise smooth too: its equilibria are refused.
"$bin" equilibria "$src/cases/examples/relay.toml" --param a --from 0.5 --to 1 > /dev/null 2> "$work/err"
check "equilibria of an equation case file with sign() exit 2" test $? -eq 2
check "... naming sign()" grep -q "relay.toml: sign() in its equations switches discontinuously, and equilibria is not built" "$work/err"
for command in "equilibria --start in-phase --param s --from 1e-8 --to 0"; do
  set -- $command
  "$bin" "$1" "$work/impulsive.toml" "${@:2}" > /dev/null 2> "$work/err"
  check "$1 on the impulsive escapement exits 2" test $? -eq 2
  check "... naming the case and its escapement" grep -q "impulsive.toml: key 'escapement': the impulsive escapement (eq. 2) switches discontinuously" "$work/err"
done

# A study file's `escapement`: Fig. 8 on the paper's escapement from the smoothed case file (its
# in-phase branch ends at a grazing near k = 83.40 N/m); checked before any work: a name that is
# none, an equation case file, [basins] of the hybrid model.
"$bin" study "$src/cases/figures/fig08_impulsive.toml" --out "$work/f8i" > "$work/out" 2> "$work/err"
check "a study with escapement = \"impulsive\" runs" test $? -eq 0
check "... its in-phase branch ends at the grazing" grep -q "in-phase .*grazing near k = 83.400" "$work/out"
check "... its anti-phase BP where the hybrid branch has it" grep -q "BP   47.06660" "$work/out"
sed 's/^escapement = "impulsive"/escapement = "smooth"/' "$src/cases/figures/fig08_impulsive.toml" | sed "s|\.\./row2.toml|$row2|" > "$work/esc.toml"
"$bin" study "$work/esc.toml" --out "$work" > /dev/null 2> "$work/err"
check "escapement = \"smooth\" exits 2" test $? -eq 2
check "... naming the key and what is expected" grep -q "esc.toml:.*escapement.*expected \"half\", \"double\" or \"impulsive\"" "$work/err"
printf 'case = "%s"\nescapement = "impulsive"\nparameter = "mu"\n[[branches]]\nname = "a"\nfrom = 0.1\nto = 0.2\n' "$src/cases/examples/hopf.toml" > "$work/esc_eq.toml"
"$bin" study "$work/esc_eq.toml" --out "$work" > /dev/null 2> "$work/err"
check "escapement with an equation case file exits 2" test $? -eq 2
check "... saying it has none" grep -q "an equation case file has no escapement" "$work/err"
# [basins] on it: runs certified against the hybrid branches' stable orbits (at k = 60 N/m the
# anti-phase orbit, stable beyond its NS point at 56.11), about 1 s.
{ sed "s|\.\./row2.toml|$row2|" "$src/cases/figures/fig08_impulsive.toml"; printf '[basins]\nfrom = 58.0\nto = 60.0\ncount = 2\nstarts = 4\nt_end = 100.0\nstart = "anti-phase"\nbox = { th1 = [0.3, 0.5] }\n'; } > "$work/esc_basins.toml"
rm -rf "$work/esc_basins"  # a walk's journal from an earlier run of this test is kept, not overwritten
"$bin" study "$work/esc_basins.toml" --out "$work/esc_basins" > "$work/out" 2> "$work/err"
check "[basins] of the impulsive escapement run" test $? -eq 0
check "... each start certified on the anti-phase orbit" grep -qE "k = 60: +anti-phase 1 .*certified 4" "$work/out"

# Options validated by the engine's one validation, in study files as on the command line.
printf 'case = "%s"\nparameter = "k"\n[[branches]]\nname = "a"\nstart = "anti-phase"\nfrom = 1.0\nto = 2.0\nstep = -0.1\n' "$row2" > "$work/step.toml"
"$bin" study "$work/step.toml" --out "$work" 2> "$work/err"
check "a study with step < 0 exits 2" test $? -eq 2
check "... naming the key and the domain" grep -q "step.toml:3: branches\[1\].step: expected a positive number" "$work/err"
"$bin" continue "$row2" --start anti-phase --param k --from 1 --to 2 --step -0.1 2> "$work/err"
check "--step -0.1 exits 2 with the same domain" grep -q -- "--step: expected a positive number" "$work/err"
# A study's accuracy preset (cases/cli/common.cpp): checked by name, applied to every branch.
printf 'case = "%s"\nparameter = "k"\naccuracy = "rough"\n[[branches]]\nname = "a"\nstart = "anti-phase"\nfrom = 1.0\nto = 2.0\n' "$row2" > "$work/accuracy.toml"
"$bin" study "$work/accuracy.toml" --out "$work" 2> "$work/err"
check "a study with accuracy = \"rough\" exits 2" test $? -eq 2
check "... naming the line, the key and the presets" grep -q "accuracy.toml:3: key 'accuracy': expected \"fast\", \"default\" or \"high\", got \"rough\"" "$work/err"
sed -i 's/"rough"/"fast"/' "$work/accuracy.toml"
"$bin" study "$work/accuracy.toml" --out "$work" > /dev/null 2> "$work/err"
check "a study with accuracy = \"fast\" runs (exit 0)" test $? -eq 0
"$bin" study "$work/accuracy.toml" --out "$work" --accuracy medium > /dev/null 2> "$work/err"
check "study --accuracy medium exits 2" grep -q -- "--accuracy medium: expected fast, default or high" "$work/err"
# A study's marks: parameter sets of the case, their value of the study's parameter in the JSON
# (Table II's k = 14.7467 and Table III's 47.0899 N/m, cases/row2.toml); an unknown set refused
# before any work, naming it.
printf 'case = "%s"\nparameter = "k"\naccuracy = "fast"\nmarks = ["table2", "table3"]\n[[branches]]\nname = "a"\nstart = "anti-phase"\nfrom = 1.0\nto = 2.0\n' "$row2" > "$work/marks.toml"
"$bin" study "$work/marks.toml" --out "$work" > /dev/null 2> "$work/err"
check "a study with marks runs (exit 0)" test $? -eq 0
check "... its JSON holds each mark's value of k" test "$(/usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print([(m['name'], m['value']) for m in j['marks']])" "$work/marks.json")" = "[('table2', 14.7467), ('table3', 47.0899)]"
sed -i 's/"table3"/"table9"/' "$work/marks.toml"
"$bin" study "$work/marks.toml" --out "$work" > /dev/null 2> "$work/err"
check "a study marking an unknown parameter set exits 2" test $? -eq 2
check "... naming the set" grep -q "table9" "$work/err"

# SIGTERM and SIGHUP stop a run after its current point or sample: complete, valid files, exit 6.
rm -f "$work/term.csv" "$work/term.json" "$work/term-events.csv"
"$bin" continue "$row2" --start anti-phase --param k --from 1 --to 100 --quiet --csv "$work/term.csv" \
  --json "$work/term.json" --events "$work/term-events.csv" > "$work/term.out" 2>&1 &
pid=$!
wait_for_lines "$work/term.csv" 4
kill -TERM $pid
wait $pid
check "SIGTERM: exit 6" test $? -eq 6
check "SIGTERM: the JSON is whole and says interrupted" test "$(json "$work/term.json" "j['stop']")" = interrupted
check "SIGTERM: one CSV row per JSON point" test "$(($(wc -l < "$work/term.csv") - 1))" -eq "$(json "$work/term.json" "len(j['points'])")"
check "SIGTERM: the events CSV has its header" grep -q '^type,k,uncertainty' "$work/term-events.csv"
rm -f "$work/hup.csv"
"$bin" simulate "$row2" --start anti-phase --t-end 400 --out "$work/hup.csv" 2> "$work/hup.err" &
pid=$!
wait_for_lines "$work/hup.csv" 100
kill -HUP $pid
wait $pid
check "SIGHUP: simulate exits 6" test $? -eq 6
check "SIGHUP: every row of the CSV is whole" \
  test "$(awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { print bad + 0 }' "$work/hup.csv")" = 0

exit $failures
