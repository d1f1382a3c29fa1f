#!/usr/bin/env bash
# The basins command end to end: identical files whatever the threads, an interrupted run
# resumed from its journal gives the files of an uninterrupted one without recomputing, bad
# options refused before any work. Small on purpose (about 3 s on two cores): 2 grid points of
# 3 starts, 30 s simulations of the row setup.
# With MPIRUN (built with MPI), the same study under mpirun with 2 and 3 ranks gives the same files.
# Usage: basins_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR [MPIRUN]
set -u
bin=$1 src=$2 work=$3 mpirun=${4:-}
rm -rf "$work"
mkdir -p "$work"
. "$(dirname "$0")/check.sh"

run=("$bin" basins "$src/cases/row2.toml" --grid k=14.7467:20:2 --starts 3 --t-end 30)
"${run[@]}" --threads 1 --out "$work/one" 2> "$work/one.err"
check "one thread exits 0" test $? -eq 0
"${run[@]}" --threads 2 --out "$work/two" 2> "$work/two.err"
check "two threads exit 0" test $? -eq 0
for f in basins_runs.csv basins_shares.csv basins.json; do
  check "$f identical with 1 and 2 threads" cmp -s "$work/one/$f" "$work/two/$f"
done
check "runs: a header and 6 rows" test "$(wc -l < "$work/one/basins_runs.csv")" -eq 7
check "runs header" test "$(head -1 "$work/one/basins_runs.csv")" = \
  "task,point,k,start,th1_0,th2_0,class,t_sync,frequency,phase_th2,amp_th1,amp_th2"
check "runs in task order" test "$(cut -d, -f1 "$work/one/basins_runs.csv" | tail -n +2 | tr '\n' ' ')" = "0 1 2 3 4 5 "
check "shares header" grep -q '^point,k,class,count,runs,share,lower,upper,t_sync_q1,t_sync_median,t_sync_q3$' "$work/one/basins_shares.csv"
check "summary prints the run time" grep -q 'run time' "$work/one.err"
check "shares: each class's t_sync quartiles those of its runs (numpy's default, 1e-12)" test "$(python3 -c "
import csv, statistics, sys
runs = list(csv.DictReader(open(sys.argv[1])))
ok = True
for s in csv.DictReader(open(sys.argv[2])):
    t = sorted(float(r['t_sync']) for r in runs if r['point'] == s['point'] and r['class'] == s['class'] and r['t_sync'] != 'nan')
    if not t:
        ok = ok and s['t_sync_median'] == 'nan'
        continue
    q = statistics.quantiles(t, n=4, method='inclusive') if len(t) > 1 else [t[0]] * 3
    ok = ok and all(abs(float(s[k]) - v) < 1e-12 for k, v in zip(('t_sync_q1', 't_sync_median', 't_sync_q3'), q))
print(ok)" "$work/one/basins_runs.csv" "$work/one/basins_shares.csv")" = True

# Under mpirun: rank 0 manages, the others simulate; the files are the same. As root in a
# container Open MPI wants --allow-run-as-root (or OMPI_ALLOW_RUN_AS_ROOT=1 and
# OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1), and --oversubscribe for more ranks than cores.
if [ -n "$mpirun" ]; then
  for np in 2 3; do
    "$mpirun" --allow-run-as-root --oversubscribe -np $np "${run[@]}" --out "$work/mpi$np" \
      2> "$work/mpi$np.err"
    check "mpirun -np $np exits 0" test $? -eq 0
    for f in basins_runs.csv basins_shares.csv basins.json; do
      check "$f identical with mpirun -np $np and 1 thread" cmp -s "$work/one/$f" "$work/mpi$np/$f"
    done
  done
  check "mpirun -np 3 runs on 2 workers" grep -q 'on 2 MPI workers' "$work/mpi3.err"
  "$mpirun" --allow-run-as-root --oversubscribe -np 8 "${run[@]}" --out "$work/mpi8" \
    2> "$work/mpi8.err"
  check "more ranks than runs exits 2" test $? -eq 2
  check "more ranks than runs: message" grep -q 'mpirun -np 8: 7 workers for 6 runs' "$work/mpi8.err"
  test ! -e "$work/mpi8/basins_journal.csv"
  check "more ranks than runs: nothing written" test $? -eq 0
fi

# Resume: a journal holding some of the runs (as an interrupted run leaves it) is continued:
# only the others are computed, and the final files equal the uninterrupted run's.
mkdir -p "$work/resumed"
head -3 "$work/one/basins_journal.csv" > "$work/resumed/basins_journal.csv"
cp "$work/one/basins_journal.csv.study" "$work/resumed/"  # the study's record, beside it
printf '4,1,20,1,0.1' >> "$work/resumed/basins_journal.csv"  # a row cut short by a kill
"${run[@]}" --threads 2 --out "$work/resumed" --resume 2> "$work/resumed.err"
check "resumed run exits 0" test $? -eq 0
check "resumed run computes only the 4 runs not in the journal" \
  grep -q '6 runs: 2 in the journal, 4 to compute' "$work/resumed.err"
for f in basins_runs.csv basins_shares.csv basins.json; do
  check "$f of the resumed run equals the uninterrupted run's" \
    cmp -s "$work/one/$f" "$work/resumed/$f"
done

# A signal stops the run after the simulation under way: exit 6, every file complete and valid
# (the journal's rows whole, the runs CSV holding them, the JSON saying it is incomplete). A longer
# study, so that the signal comes while it runs (40 starts: about 4 s if it were not stopped).
"$bin" basins "$src/cases/row2.toml" --grid k=14.7467 --starts 40 --t-end 30 --threads 1 \
  --out "$work/signal" 2> "$work/signal.err" &
pid=$!
wait_for_lines "$work/signal/basins_journal.csv" 2
kill -TERM $pid
wait $pid
check "SIGTERM exits 6" test $? -eq 6
check "interrupted run says so" grep -q 'INTERRUPTED' "$work/signal.err"
check "interrupted run's journal rows are whole" \
  awk -F, 'END { exit !(NR >= 2) } NF != 12 { exit 1 }' "$work/signal/basins_journal.csv"
check "interrupted run's runs CSV holds the journal's rows" test \
  "$(wc -l < "$work/signal/basins_runs.csv")" -eq "$(wc -l < "$work/signal/basins_journal.csv")"
check "interrupted run's JSON is valid and says it is incomplete" python3 -c \
  "import json,sys; d=json.load(open(sys.argv[1])); sys.exit(0 if not d['complete'] else 1)" \
  "$work/signal/basins.json"

# A basins study file (a TOML file with a `case` key) gives the same study as the options.
cat > "$work/small.toml" <<EOF
title = "small"
case = "$src/cases/row2.toml"
starts = 3
t_end = 30.0
[[grid]]
parameter = "k"
from = 14.7467
to = 20
count = 2
EOF
"$bin" basins "$work/small.toml" --threads 2 --out "$work/file" 2> "$work/file.err"
check "study file exits 0" test $? -eq 0
for f in basins_runs.csv basins_shares.csv; do
  check "$f of the study file equals the options' run" cmp -s "$work/one/$f" "$work/file/$f"
done
check "study file run names its title" grep -q "small.toml: small" "$work/file.err"
"$bin" basins "$work/small.toml" --starts 5 --out "$work/bad" 2> "$work/bad.err"
check "an option the study file sets exits 2" test $? -eq 2
check "an option the study file sets is named" \
  grep -q -- "--starts: given with the basins study file" "$work/bad.err"
sed 's/^count = 2$/count = 0/' "$work/small.toml" > "$work/bad.toml"
"$bin" basins "$work/bad.toml" --out "$work/bad" 2> "$work/bad.err"
check "bad study file value exits 2" test $? -eq 2
check "bad study file value: file, line and key" \
  grep -q "bad.toml:9: key 'grid\[1\].count': expected at least one value" "$work/bad.err"
sed 's/^starts = 3$/start = 3/' "$work/small.toml" > "$work/bad.toml"
"$bin" basins "$work/bad.toml" --out "$work/bad" 2> "$work/bad.err"
check "unknown study file key: file, line and key" \
  grep -q "bad.toml:3: key 'start': expected one of the keys" "$work/bad.err"

# Bad input: refused before any work (exit 2), naming the option.
bad() {  # bad DESCRIPTION PATTERN ARGS... (--out DIR: the last one given)
  local what=$1 pattern=$2; shift 2
  local out=("--out" "$work/bad")
  [[ " $* " == *" --out "* ]] && out=()
  "$bin" basins "$src/cases/row2.toml" "${out[@]}" "$@" 2> "$work/bad.err"
  local code=$?
  check "$what exits 2" test $code -eq 2
  check "$what: message" grep -q -- "$pattern" "$work/bad.err"
}
bad "no grid" "--grid: expected one or two" --starts 3
bad "empty grid" "--grid: expected at least one value" --grid k=40:90:0
bad "malformed grid" "--grid k=40:90: expected NAME=FROM:TO:COUNT" --grid k=40:90
bad "unknown grid parameter" "grid parameter 'q' is not one of" --grid q=1:2:2
bad "grid outside the domain" "M = -0.1 is outside the model's domain" --grid M=-0.1:0.3:3
bad "reversed angle bounds" "--angles 0.5:-0.5: the bounds are reversed" --grid k=40 --angles 0.5:-0.5
bad "drawn angle given" "--initial th1=0.2: the pendula's start angles are drawn" --grid k=40 --initial th1=0.2
bad "unknown start state" "unknown state 'z'" --grid k=40 --initial z=0.01
bad "zero starts" "--starts: expected at least one start" --grid k=40 --starts 0
bad "zero threads" "--threads: expected a positive number" --grid k=40 --threads 0
bad "run shorter than the window" "--t-end: expected a time longer than the classifier's window" --grid k=40 --t-end 5
bad "journal of an earlier run without --resume" "is the journal of an earlier run" --grid k=14.7467:20:2 --out "$work/one"
bad "journal of another study" "a journal of another study: option --t-end was 30 when the journal was started, now not given; option --seed was not given when the journal was started, now 2" --grid k=14.7467:20:2 --starts 3 --seed 2 --out "$work/one" --resume
# Issue 32: a journal resumed with other parameters kept its rows and computed the rest under the
# new ones. Every option that changes a result is in the study's record; the threads are not.
bad "journal resumed with another --set" "a journal of another study: option --set was not given when the journal was started, now c=0.1" \
  --grid k=14.7467:20:2 --starts 3 --t-end 30 --set c=0.1 --out "$work/one" --resume
bad "journal resumed with another --t-end" "option --t-end was 30 when the journal was started, now 31" \
  --grid k=14.7467:20:2 --starts 3 --t-end 31 --out "$work/one" --resume
cp "$src/cases/row2.toml" "$work/changed.toml"
"$bin" basins "$work/changed.toml" --grid k=14.7467:20:2 --starts 3 --t-end 30 --out "$work/changed" 2> /dev/null
printf '\n# an edit\n' >> "$work/changed.toml"
"$bin" basins "$work/changed.toml" --grid k=14.7467:20:2 --starts 3 --t-end 30 --out "$work/changed" --resume 2> "$work/changed.err"
check "a journal resumed after its case file changed: exit 2" test $? -eq 2
check "... naming the case file" grep -q "file case file has changed since the journal was started" "$work/changed.err"
bad "a journal without the orbit columns resumed with --confirm" "the journal's header is" \
  --grid k=14.7467:20:2 --starts 3 --t-end 30 --confirm --out "$work/one" --resume
test ! -e "$work/bad/basins_journal.csv"
check "nothing written on bad input" test $? -eq 0

# Early stop (--early-stop): at Table II, k = 60 N/m, 32 starts of 100 s (seed 1), each run
# stopped once certified to converge to a stable orbit reached from the case's starts, gives
# every run the class and time to synchronize (within one sample, 0.01 s) of the full-length run;
# no run stops before its time to synchronize (six of these synchronize at 72-82 s, after about
# 20 s near the unstable lower in-phase orbit); the runs stop 1.5 times sooner on average.
"$bin" basins "$src/cases/row2.toml" --params table2 --grid k=60 --starts 32 --t-end 100 \
  --threads 2 --out "$work/full60" 2> /dev/null
"$bin" basins "$src/cases/row2.toml" --params table2 --grid k=60 --starts 32 --t-end 100 \
  --threads 2 --early-stop --out "$work/early60" 2> "$work/early60.err"
check "early stop exits 0" test $? -eq 0
check "... the same classes and times to synchronize, never stopped before them" test "$(python3 -c "
import csv, sys
full = list(csv.DictReader(open(sys.argv[1])))
early = list(csv.DictReader(open(sys.argv[2])))
slow = [r for r in full if float(r['t_sync']) > 72]
ok = len(full) == len(early) == 32 and len(slow) >= 6
for a, b in zip(full, early):
    ok = ok and a['class'] == b['class'] and abs(float(a['t_sync']) - float(b['t_sync'])) <= 0.01
    ok = ok and b['certified_by'] in ('anti-phase', '-') and float(b['stopped_at']) >= float(a['t_sync']) - 0.01
ok = ok and sum(float(b['stopped_at']) for b in early) < 0.8 * 100 * 32
print(ok)" "$work/full60/basins_runs.csv" "$work/early60/basins_runs.csv")" = True

exit $failures
