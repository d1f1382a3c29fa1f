#!/usr/bin/env bash
# The fit command end to end: recordings made by `simulate` with known parameters and Gaussian
# noise (fixed seed), fitted back; the fitted case file run unchanged through simulate, orbit
# and continue; bad data rejected with exit code 2 and a message naming file, line and column.
# Usage: fit_test.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
mkdir -p "$work"
. "$(dirname "$0")/check.sh"
. "$(dirname "$0")/damped_oscillator.sh"
json() { /usr/bin/python3 -c "import json,sys; j=json.load(open(sys.argv[1])); print($2)" "$1"; }
# noisy IN OUT COLUMN SIGMA SEED: a recording of one column with Gaussian noise (scripts/add_noise).
noisy() { "$src/scripts/add_noise" "$1" "$2" --columns "$3" --sigma "$4" --seed "$5"; }
# within TRUTH JSON NAME K: |value - TRUTH| < K standard errors
within() {
  test "$(json "$2" "abs(j['values']['$3'] - $1) < $4 * j['errors']['$3']")" = True
}

# d and s from one metronome's angle: Table I's d = 2.4e-6, s = 4.51e-5 (cases/single.toml),
# 10 s every 0.02 s, noise 0.005 rad; the fit starts at d = 2e-6, s = 5.4e-5.
"$bin" simulate "$src/cases/single.toml" --start swing --t-end 10 --dt 0.02 --rtol 1e-11 \
  --atol 1e-13 --out "$work/single.csv" 2> /dev/null
noisy "$work/single.csv" "$work/angle.csv" th1 0.005 3
"$bin" fit "$src/cases/single.toml" --data "$work/angle.csv" --free d,s --free-initial th1 \
  --set d=2e-6 --set s=5.4e-5 --out "$work/single_fitted.toml" --json "$work/single.json" \
  --csv "$work/single_model.csv" > "$work/single.out"
check "fit exits 0" test $? -eq 0
check "report gives fitted values with standard errors" grep -q '^               d  .*e-06 .*e-0' "$work/single.out"
check "report gives the residual RMS" grep -q '^  residuals    RMS th1 0.00' "$work/single.out"
check "report gives the evaluations" grep -q '^  work         [0-9]* evaluations' "$work/single.out"
check "report gives the run time" grep -q '^  run time' "$work/single.out"
check "JSON: converged" test "$(json "$work/single.json" "j['converged']")" = True
check "true d within 3 standard errors" within 2.4e-6 "$work/single.json" d 3
check "true s within 3 standard errors" within 4.51e-5 "$work/single.json" s 3
check "true th1(0) within 3 standard errors" within 0.3 "$work/single.json" 'th1(0)' 3
check "residual RMS within 10% of the noise 0.005" \
  test "$(json "$work/single.json" "abs(j['residual_rms']['th1'] / 0.005 - 1) < 0.1")" = True
check "model CSV: one row per sample, every state" \
  test "$(head -1 "$work/single_model.csv"),$(wc -l < "$work/single_model.csv")" = "t,x,th1,vx,vth1,502"

# The fitted case runs unchanged, with the fitted values.
f=$work/single_fitted.toml
check "fitted case keeps the comments" grep -q '^d = .* # fitted to angle.csv, std. error .* (was 2.4e-6) | N m s, hinge damping' "$f"
"$bin" simulate "$f" --start swing --t-end 2 --out "$work/fitted_sim.csv" 2> /dev/null
check "fitted case: simulate exits 0" test $? -eq 0
"$bin" orbit "$f" --start swing --transient 20 --json "$work/fitted_orbit.json" > /dev/null
check "fitted case: orbit exits 0" test $? -eq 0
check "fitted case: the orbit uses the fitted d" \
  test "$(json "$work/fitted_orbit.json" "j['params']['d']")" = "$(json "$work/single.json" "j['values']['d']")"
"$bin" continue "$f" --start swing --transient 20 --param s --from 4.4e-5 --to 4.6e-5 \
  --max-points 4 --quiet > /dev/null 2>&1
check "fitted case: continue exits 0" test $? -eq 0

# c and k from the row setup's platform with the pendula locked (Table II: c = 0.0185,
# k = 14.7467), released from 1 cm, 20 s every 0.01 s, noise 0.1 mm; start c = 0.03, k = 12.
"$bin" simulate "$src/cases/row2.toml" --locked-pendula --initial x=0.01 --t-end 20 \
  --rtol 1e-11 --atol 1e-14 --out "$work/decay.csv" 2> "$work/decay.err"
check "simulate --locked-pendula writes t,x,vx" test "$(head -1 "$work/decay.csv")" = "t,x,vx"
noisy "$work/decay.csv" "$work/platform.csv" x 1e-4 4
"$bin" fit "$src/cases/row2.toml" --locked-pendula --data "$work/platform.csv" --free c,k \
  --free-initial x --set c=0.03 --set k=12 --out "$work/row2_fitted.toml" \
  --json "$work/platform.json" > "$work/platform.out"
check "locked-pendula fit exits 0" test $? -eq 0
check "true c within 3 standard errors" within 0.0185 "$work/platform.json" c 3
check "true k within 3 standard errors" within 14.7467 "$work/platform.json" k 3
f=$work/row2_fitted.toml
check "fitted row case: c and k replaced in [params.table2]" \
  test "$(grep -c '^[ck] = .*# fitted to platform.csv' "$f")" = 2
"$bin" simulate "$f" --start in-phase --t-end 2 2> /dev/null
check "fitted row case: simulate exits 0" test $? -eq 0
"$bin" orbit "$f" --start anti-phase > /dev/null
check "fitted row case: orbit exits 0" test $? -eq 0
"$bin" continue "$f" --start anti-phase --param k --from 14 --to 16 --max-points 3 --quiet \
  > /dev/null 2>&1
check "fitted row case: continue exits 0" test $? -eq 0

# The plot.
if /usr/bin/python3 -c "import matplotlib" 2> /dev/null; then
  (cd "$work" && "$src/scripts/plot_fit" single.json --out "$work/single.png" > /dev/null)
  check "plot_fit draws the fit" test -s "$work/single.png"
fi

# Bad data: exit 2, nothing computed, the file, line and column named.
bad() {  # bad NAME CONTENT EXPECTED-MESSAGE [fit options]
  local name=$1 content=$2 expected=$3; shift 3
  printf "$content" > "$work/$name.csv"
  "$bin" fit "$src/cases/row2.toml" --locked-pendula --data "$work/$name.csv" "$@" \
    > /dev/null 2> "$work/$name.err"
  check "$name: exit 2" test $? -eq 2
  check "$name: message" grep -qF -- "$expected" "$work/$name.err"
}
bad unknown_column 't,x,th1\n0,0.01,0.3\n0.1,0.008,0.29\n' \
  "unknown_column.csv:1: column 3 'th1' is not a state of the platform with locked pendula (--locked-pendula); expected t, then any of: x, vx" --free c
bad missing_columns 't\n0\n0.1\n' \
  "missing_columns.csv:1: only a time column; expected t, then one or more of: x, vx" --free c
bad time_not_increasing 't,x\n0,0.01\n0.1,0.008\n0.1,0.005\n' \
  "time_not_increasing.csv:4: column 't': time 0.1 after 0.1 (line 3); expected strictly increasing times" --free c
bad nan 't,x\n0,0.01\n0.1,nan\n' \
  "nan.csv:3: column 'x' (field 2): expected a finite number, got 'nan'" --free c
bad empty_row 't,x\n0,0.01\n\n0.2,0.004\n' "empty_row.csv:3: empty row; expected 2 fields (t, x)" --free c
bad missing_field 't,x,vx\n0,0.01,0\n0.1,0.008\n' \
  "missing_field.csv:3: expected 3 fields (t, x, vx), got 2" --free c
bad too_few 't,x\n0,0.01\n0.1,0.008\n0.2,0.004\n' \
  "too_few.csv: 3 samples of x give 2 residuals (the first row fixes the initial state); fitting 2 unknowns (c, k) needs more than 2: expected more samples" --free c,k
bad unknown_parameter 't,x\n0,0.01\n0.1,0.008\n0.2,0.004\n' \
  "--free kk: the case $src/cases/row2.toml has no parameter 'kk'; expected one of: M, c, k" --free kk

# An equation case file: the damped oscillator x'' + 2 zeta w x' + w^2 x = 0, whose solution from
# x(0) = 1, x'(0) = -zeta w is x = exp(-zeta w t) cos(w_d t), w_d = w sqrt(1 - zeta^2). Exact
# samples of x at w = 1, zeta = 0.05 (t = 0 .. 20 by 0.1), fitted from w = 1.2, zeta = 0.08 (v
# starts at the file's [states], the true -zeta w): both recovered to 1e-6 (the integration's
# accuracy at the fit's defaults, far below it).
write_damped_oscillator "$work"
SYMPATHY_CACHE_DIR="$work/cache" "$bin" fit "$work/oscillator.toml" --data "$work/oscillator.csv" \
  --free w,zeta --json "$work/oscillator.json" > "$work/oscillator.out" 2>&1
check "fit on an equation case file exits 0" test $? -eq 0
check "... unrecorded v from the file's [states]" grep -q "v -0.05 (\[states\])" "$work/oscillator.out"
check "... recovers w = 1 and zeta = 0.05 to 1e-6" test "$(json "$work/oscillator.json" "abs(j['values']['w'] - 1) < 1e-6 and abs(j['values']['zeta'] - 0.05) < 1e-6")" = True
for option in --locked-pendula "--out $work/fitted.toml"; do
  # shellcheck disable=SC2086
  SYMPATHY_CACHE_DIR="$work/cache" "$bin" fit "$work/oscillator.toml" --data "$work/oscillator.csv" \
    --free w $option > /dev/null 2> "$work/eq_option.err"
  check "fit $option on an equation case file: exit 2" test $? -eq 2
  check "... saying it is for metronome case files" grep -qF -- "${option%% *}: only for a metronome case file" "$work/eq_option.err"
done

"$bin" fit --help > "$work/help.out"
check "--help exits 0 and lists --free-initial" grep -q -- "--free-initial" "$work/help.out"

exit $failures
