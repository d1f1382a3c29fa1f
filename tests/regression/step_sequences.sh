#!/usr/bin/env bash
# Located events do not depend on the step sequence beyond their reported uncertainty: the row
# setup's anti-phase k-branch (BP, NS, NS) and M-branch (BP, NS, NS) each computed with three
# step sequences (initial and largest step varied), every event of each run within the sum of
# the two runs' reported uncertainties of every other run's, and each uncertainty 1e-8 relative
# or better (the switching issue's requirement on the k- and M-branches).
# usage: tests/regression/step_sequences.sh SYMPATHY_BINARY SOURCE_DIR WORK_DIR
set -u
bin=$1 src=$2 work=$3
mkdir -p "$work"
. "$src/tests/cli/check.sh"
row2=$src/cases/row2.toml
for param in k M; do
  if [ $param = k ]; then range=(--from 44 --to 58); else range=(--from 0.12 --to 0.05); fi
  n=0
  for steps in "0.02 0.1" "0.005 0.03" "0.05 0.2"; do
    set -- $steps
    n=$((n + 1))
    "$bin" continue "$row2" --start anti-phase --param $param "${range[@]}" --step "$1" \
      --max-step "$2" --quiet --json "$work/$param-$n.json" > "$work/$param-$n.out" 2>&1
    check "$param-branch with steps $steps exits 0" test $? -eq 0
  done
  check "$param-branch: the events agree within their uncertainties, each 1e-8 relative or better" \
    /usr/bin/python3 - "$work/$param-1.json" "$work/$param-2.json" "$work/$param-3.json" <<'PY'
import json, sys
runs = [json.load(open(p))["events"] for p in sys.argv[1:]]
ok = True
types = [[e["type"] for e in r] for r in runs]
if any(t != types[0] for t in types) or len(types[0]) != 3:
    print("event types differ or are not three:", types)
    sys.exit(1)
for i, r in enumerate(runs):
    for j, s in enumerate(runs):
        for a, b in zip(r, s):
            if abs(a["value"] - b["value"]) > a["uncertainty"] + b["uncertainty"]:
                print(f"{a['type']}: run {i + 1} {a['value']:.12g} +- {a['uncertainty']:.1e}, "
                      f"run {j + 1} {b['value']:.12g} +- {b['uncertainty']:.1e}")
                ok = False
    for a in r:
        rel = a["uncertainty"] / abs(a["value"])
        print(f"run {i + 1} {a['type']} {a['value']:.12g} uncertainty {a['uncertainty']:.1e} ({rel:.1e} relative)")
        ok = ok and rel <= 1e-8
sys.exit(0 if ok else 1)
PY
done
exit "$failures"
