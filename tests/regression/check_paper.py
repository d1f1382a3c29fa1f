#!/usr/bin/python3
"""Checks computed studies against the paper's findings (MODEL.md, "What the paper found").

usage: check_paper.py STUDY_DIR

The figures give ranges, not digits: these checks hold the qualitative picture and the
approximate parameter values the paper states, and the type of every located point.
Resonances come from MODEL.md's damped platform frequency
fd = sqrt(k/Mt) sqrt(1 - z^2) / (2 pi), z = c / (2 sqrt(k Mt)), set equal to the anti-phase
orbit's frequency (its platform stands still, so that frequency is the metronomes' own).
"""
import json
import math
import os
import sys

TABLE1_PAIR = 2 * (0.0185 + 0.0086)  # kg: two metronomes' mp + mb (Table I)
failures = 0


def check(condition, what):
    global failures
    print(("ok     " if condition else "FAILED ") + what)
    failures += not condition


def load(folder, study):
    with open(os.path.join(folder, study + ".json")) as f:
        return {b["name"]: b for b in json.load(f)["branches"]}


def stable_at(branch, value):
    point = min(branch["points"], key=lambda p: abs(p["value"] - value))
    return point["stable"]


def events(branch, kind=None):
    return [e for e in branch["events"] if kind is None or e["type"] == kind]


def damped_frequency(k, mt, c):
    z = c / (2 * math.sqrt(k * mt))
    return math.sqrt(k / mt) * math.sqrt(1 - z * z) / (2 * math.pi)


def solve(f, lo, hi):  # bisection for a sign change of f on [lo, hi]
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if (f(lo) > 0) == (f(mid) > 0):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = sys.argv[1]

    # Row setup versus k (Fig. 8): Table II, M = 0.3778 kg, c = 0.0185 N s/m.
    b = load(folder, "fig08")
    inph, anti = b["in-phase"], b["anti-phase"]
    check(all(p["stable"] for p in inph["points"] if p["value"] <= 75),
          "fig08: in-phase stable over k = 1-75 N/m")
    check([e["type"] for e in events(anti)] == ["BP", "NS", "NS"],
          "fig08: anti-phase events are BP, NS, NS")
    f_anti = 1.0 / anti["points"][0]["period"]
    k_res = solve(lambda k: damped_frequency(k, 0.3778 + TABLE1_PAIR, 0.0185) - f_anti, 1, 100)
    bp = events(anti, "BP")[0]["value"] if events(anti, "BP") else float("nan")
    check(44 < bp < 50, f"fig08: anti-phase stable from about 47 N/m (BP at {bp:.4f})")
    ns = sorted(e["value"] for e in events(anti, "NS"))
    check(len(ns) == 2 and ns[0] < k_res < ns[1] and bp < ns[0],
          f"fig08: anti-phase unstable window {ns} at the resonance k = {k_res:.3f}")
    check(not stable_at(anti, 30) and stable_at(anti, 0.5 * (bp + ns[0])) and
          not stable_at(anti, 0.5 * (ns[0] + ns[1])) and stable_at(anti, 90),
          "fig08: anti-phase unstable, stable, unstable (window), stable along k")

    # Row setup versus M (Fig. 6): Table II, k = 14.7467 N/m, c = 0.0185 N s/m.
    b = load(folder, "fig06")
    inph, anti = b["in-phase"], b["anti-phase"]
    check(all(p["stable"] for p in inph["points"] if 0.05 <= p["value"] <= 0.4),
          "fig06: in-phase stable over M = 0.05-0.4 kg")
    check([e["type"] for e in events(anti)] == ["BP", "NS", "NS"],
          "fig06: anti-phase events are BP, NS, NS (from M = 0.4 down)")
    m_res = solve(lambda m: damped_frequency(14.7467, m + TABLE1_PAIR, 0.0185) - f_anti, 0.01, 0.4)
    bp = events(anti, "BP")[0]["value"] if events(anti, "BP") else float("nan")
    ns = sorted(e["value"] for e in events(anti, "NS"))
    check(0.09 < bp < 0.13, f"fig06: in- and anti-phase coexist below about 0.12 kg (BP {bp:.5f})")
    check(len(ns) == 2 and ns[0] < 0.075 < ns[1] and ns[0] < m_res < ns[1],
          f"fig06: anti-phase unstable around 0.075 kg: window {ns}, resonance M = {m_res:.4f}")

    # Row setup versus c (Fig. 7): neither orbit stable between about 12 and 19 N s/m.
    b = load(folder, "fig07")
    inph, anti = b["in-phase"], b["anti-phase"]
    check([e["type"] for e in events(inph)] == ["BP"] and [e["type"] for e in events(anti)] == ["BP"],
          "fig07: one BP on each branch")
    c_in, c_anti = events(inph)[0]["value"], events(anti)[0]["value"]
    check(stable_at(inph, 0.5 * c_in) and not stable_at(inph, 0.5 * (c_in + 25)),
          f"fig07: in-phase turns unstable at c = {c_in:.4f}")
    check(not stable_at(anti, 0.5 * c_anti) and stable_at(anti, 0.5 * (c_anti + 25)),
          f"fig07: anti-phase becomes stable at c = {c_anti:.4f} (paper: near 20)")
    check(c_in < 16 < c_anti and c_in < 19 and c_anti > 12 and 17 < c_anti < 25,
          "fig07: an interval with neither stable contains c = 16 and overlaps 12-19")

    # Cross setup with virtual spring versus k (Fig. 20): Table IV.
    b = load(folder, "fig20")
    inph, anti = b["in-in"], b["anti-anti"]
    check(all(p["stable"] for p in inph["points"] if p["value"] <= 100),
          "fig20: in-in stable over k = 1-100 N/m")
    check(not stable_at(anti, 24.3431) and not stable_at(anti, 62.8719),
          "fig20: anti-anti unstable at Table IV's and Table V's k")
    stable_ks = [p["value"] for p in anti["points"] if p["stable"]]
    check(bool(stable_ks) and min(stable_ks) > 75,
          f"fig20: anti-anti stable only at much larger k (from {min(stable_ks, default=0):.2f})")

    # Accuracy (the accuracy report's promise at default settings): the trivial multiplier within
    # 1e-8 of 1 on every point of every branch, the small-amplitude in-phase orbits at small M
    # (fig06) and large k (fig08) included, and the spring setup's anti-anti branch, where a
    # family's multiplier sits at 1 beside the trivial one (their values from the compression of
    # the monodromy onto f and the family, floquet.cpp).
    for study in ["fig06", "fig07", "fig08", "fig20"]:
        for name, branch in load(folder, study).items():
            limit = 1e-8
            worst = max(p["trivial_multiplier_error"] for p in branch["points"])
            check(worst < limit, f"{study}/{name}: trivial multiplier error at most {worst:.1e} "
                                 f"over {len(branch['points'])} points (limit {limit:g})")

    print(f"{failures} failure(s)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
