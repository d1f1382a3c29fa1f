#!/usr/bin/python3
"""Compares the bifurcation points of computed studies, and the ends of computed two-parameter
curves, with the goldens.

usage: check_goldens.py GOLDENS.json STUDY_DIR [--perturb]

Every golden branch must have the same events, in order, with the same types, and each value
within its tolerance of the golden one: twice the uncertainty the computation reports for that
event (its bracket plus its multipliers' error over the crossing speed), and at least the
absolute floor. With --perturb the first golden value is moved by ten of its tolerances first:
the check must then fail (it shows that it can).
Exit code 0 when everything matches, 1 otherwise, with a table of what differs.
"""
import json
import os
import sys


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 2:
        sys.exit(__doc__)
    goldens_path, folder = args
    with open(goldens_path) as f:
        goldens = json.load(f)
    absolute = goldens["tolerance"]["absolute"]
    studies = goldens["studies"]
    perturb = "--perturb" in sys.argv

    failures = 0
    for study, branches in studies.items():
        path = os.path.join(folder, study + ".json")
        if not os.path.exists(path):
            print(f"FAILED {study}: no computed {path}")
            failures += 1
            continue
        with open(path) as f:
            computed = {b["name"]: b for b in json.load(f)["branches"]}
        for name, expected in branches.items():
            events = [e for e in computed.get(name, {}).get("events", [])]
            got = [(e["type"], e["value"], e["uncertainty"]) for e in events]
            want = [(e["type"], e["value"]) for e in expected]
            if [t for t, _, _ in got] != [t for t, _ in want]:
                print(f"FAILED {study}/{name}: types {[t for t, _, _ in got]} != {[t for t, _ in want]}")
                failures += 1
                continue
            for (t, v, u), (_, w) in zip(got, want):
                tol = max(2.0 * u, absolute)
                if perturb:
                    w += 10 * tol
                    perturb = False
                ok = abs(v - w) <= tol
                failures += not ok
                print(f"{'ok    ' if ok else 'FAILED'} {study}/{name} {t} {v:.10g} golden {w:.10g} "
                      f"diff {v - w:+.2e} tolerance {tol:.1e}")
    # Two-parameter curves (tests/regression/curves.sh): the kind, and the first and the last
    # point, each at its golden second-parameter value (the start's and the window's edge), the
    # first parameter within twice its reported uncertainty.
    for name, expected in goldens.get("curves", {}).items():
        path = os.path.join(folder, f"curve-{name}.json")
        if not os.path.exists(path):
            print(f"FAILED curve {name}: no computed {path}")
            failures += 1
            continue
        with open(path) as f:
            curve = json.load(f)
        if curve["kind"] != expected["kind"] or not curve["points"]:
            print(f"FAILED curve {name}: kind {curve['kind']} != {expected['kind']} or no points")
            failures += 1
            continue
        for end, point in (("start", curve["points"][0]), ("end", curve["points"][-1])):
            want = expected[end]
            tol = max(2.0 * (point["uncertainty"] or 0.0), absolute)
            w = want["first"]
            if perturb:
                w += 10 * tol
                perturb = False
            ok = abs(point["first"] - w) <= tol and abs(point["second"] - want["second"]) <= absolute
            failures += not ok
            print(f"{'ok    ' if ok else 'FAILED'} curve {name} {end} at {point['second']:.10g}: "
                  f"{point['first']:.10g} golden {w:.10g} diff {point['first'] - w:+.2e} "
                  f"tolerance {tol:.1e}")
    print(f"{failures} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
