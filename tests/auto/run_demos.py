#!/usr/bin/env python3
"""AUTO-07p's demos as a regression suite for sympathy (issue 33, item 1).

    run_demos.py SYMPATHY SOURCE_DIR [--demo NAME]... [--keep DIR] [--verbose]

Runs every command of tests/auto/runs.txt with the sympathy program SYMPATHY (one compile cache,
a fresh private directory, for the whole suite), reads their --json outputs and holds each line
of tests/auto/references.csv (the special points AUTO-07p's regression log test/hyper.all prints
for the same runs) against them. Python 3 standard library only. See tests/auto/README.md.

A reference is matched to the run's event of the same kind (AUTO's TR is sympathy's NS, a
regular point PT is asked for as a user point UZ) nearest to it in the parameter (and period,
when the reference has one). Outcomes, one line per reference:

  PASS   the event is within the reference's precision (value, and period when given) and
         trusted (continue: the event's "trusted"; equilibria: its "located")
  FAIL   expected to pass and did not: no such event, not trusted, or the run failed
  WRONG  a trusted event near the reference (within 100 precisions, or 1e-3 relative) but
         outside its precision: an error unless the reference is marked xfail
  XFAIL  marked xfail and not passing (today's known failures, with their reason)
  XPASS  marked xfail but passing now: an error, so that the marker gets flipped to pass

Exit code 0 when every reference is PASS or XFAIL, 1 otherwise, 2 on bad input.
"""

import csv
import json
import math
import os
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))

# AUTO's label -> the event type sympathy reports for it.
KIND_TO_EVENT = {"HB": "HB", "LP": "LP", "BP": "BP", "PD": "PD", "TR": "NS", "NS": "NS",
                 "UZ": "UZ", "PT": "UZ",
                 # codimension-two points on curves of equilibria (AUTO's and MatCont's labels)
                 "BT": "BT", "CP": "CP", "GH": "GH", "ZH": "ZH", "HH": "HH"}


def usage(message):
    sys.stderr.write("run_demos.py: %s\n" % message)
    sys.stderr.write(__doc__.split("\n\n")[1] + "\n")
    sys.exit(2)


def read_runs(path):
    """runs.txt: 'DEMO RUN TIMEOUT COMMAND...' per line; '#' starts a comment."""
    runs = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            words = shlex.split(line)
            if len(words) < 4:
                usage("%s:%d: expected DEMO RUN TIMEOUT COMMAND..." % (path, number))
            runs.append({"demo": words[0], "run": words[1], "timeout": float(words[2]),
                         "args": words[3:], "line": number})
    return runs


def read_references(path):
    references = []
    with open(path, newline="") as f:
        rows = csv.DictReader(line for line in f if not line.lstrip().startswith("#"))
        for number, row in enumerate(rows, 2):
            try:
                reference = {
                    "demo": row["demo"].strip(), "run": row["run"].strip(),
                    "kind": row["kind"].strip(), "parameter": row["parameter"].strip(),
                    "value": float(row["value"]),
                    "period": float(row["period"]) if row["period"].strip() else None,
                    "precision": float(row["precision"]),
                    "period_precision": (float(row["period_precision"])
                                         if row["period_precision"].strip() else None),
                    "norm": float(row["norm"]) if (row.get("norm") or "").strip() else None,
                    "norm_precision": (float(row["norm_precision"])
                                       if (row.get("norm_precision") or "").strip() else None),
                    "norm_of": (row.get("norm_of") or "").split(),
                    "status": row["status"].strip(), "reason": (row["reason"] or "").strip(),
                    "extremes": read_extremes(row.get("extremes") or ""),
                }
            except (KeyError, ValueError, AttributeError) as error:
                usage("%s: row %d: %s" % (path, number, error))
            if reference["kind"] not in KIND_TO_EVENT:
                usage("%s: row %d: unknown kind %r" % (path, number, reference["kind"]))
            if reference["status"] not in ("pass", "xfail"):
                usage("%s: row %d: status must be pass or xfail" % (path, number))
            if reference["period"] is not None and reference["period_precision"] is None:
                usage("%s: row %d: a period needs its period_precision" % (path, number))
            if reference["norm"] is not None and reference["norm_precision"] is None:
                usage("%s: row %d: a norm needs its norm_precision" % (path, number))
            reference["row"] = number
            references.append(reference)
    return references


def printed_precision(text):
    """Half a unit of the last digit printed in text (AUTO's 1.99585E+00: 5e-6), or 1e-5 of
    the value, whichever is larger: the precision rule of the other columns."""
    mantissa, _, exponent = text.upper().partition("E")
    decimals = len(mantissa.partition(".")[2])
    half_unit = 0.5 * 10.0 ** (int(exponent or 0) - decimals)
    return max(half_unit, 1e-5 * abs(float(text)))


def read_extremes(text):
    """'max:NAME=VALUE min:NAME=VALUE~PRECISION ...': a state's largest or smallest value over
    the orbit (AUTO's MAX U(i), MIN U(i) columns), held to VALUE's printed precision or to the
    PRECISION given after ~ (an independent value's)."""
    extremes = []
    for word in text.split():
        what, _, value = word.partition("=")
        which, _, name = what.partition(":")
        value, _, precision = value.partition("~")
        if which not in ("max", "min") or not name or not value:
            raise ValueError("extremes: expected max:NAME=VALUE or min:NAME=VALUE, got %r" % word)
        extremes.append({"which": which, "name": name, "value": float(value),
                         "precision": float(precision) if precision else printed_precision(value)})
    return extremes


def expand(args, source_dir, out, outputs):
    expanded = []
    for word in args:
        word = word.replace("{src}", source_dir).replace("{auto}", HERE).replace("{out}", out)
        for name, path in outputs.items():
            word = word.replace("{json:%s}" % name, path)
        expanded.append(word)
    return expanded


def run_all(sympathy, source_dir, runs, work, verbose):
    """Runs the commands in order (a run may read an earlier one's JSON: {json:RUN})."""
    results = {}
    outputs = {}
    for run in runs:
        key = (run["demo"], run["run"])
        out = os.path.join(work, "%s-%s.json" % key)
        outputs_of_demo = {name: path for (demo, name), path in outputs.items()
                           if demo == run["demo"]}
        command = [sympathy] + expand(run["args"], source_dir, out, outputs_of_demo)
        start = time.monotonic()
        try:
            completed = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                       timeout=run["timeout"], universal_newlines=True)
            code = completed.returncode
            stderr = completed.stderr
        except subprocess.TimeoutExpired:
            code, stderr = "timeout", "killed after %g s" % run["timeout"]
        seconds = time.monotonic() - start
        data = None
        if os.path.exists(out):
            with open(out) as f:
                data = json.load(f)
        outputs[key] = out
        results[key] = {"code": code, "data": data, "seconds": seconds, "stderr": stderr,
                        "command": command}
        note = "" if code == 0 else "  (exit %s: %s)" % (code, stderr.strip().splitlines()[-1]
                                                         if stderr.strip() else "")
        print("run %-5s %-10s %6.2f s%s" % (run["demo"], run["run"], seconds, note), flush=True)
        if verbose:
            print("    " + " ".join(shlex.quote(word) for word in command))
    return results


def event_trusted(event):
    if "trusted" in event:
        return bool(event["trusted"])
    return bool(event.get("located", False))  # equilibria: no trust field; located by regula falsi


def event_norm(event, state_names, states):
    """AUTO's L2-NORM of an orbit: sqrt of the sum over the states of their mean squares over
    the period (sympathy's rms per state); of an equilibrium, the Euclidean norm of the state."""
    values = event.get("rms")
    if values is None and "state" in event and "period" not in event:
        values = event["state"]
    if values is None:
        return None
    if isinstance(values, dict):
        values = [values[name] for name in state_names]
    chosen = [v for name, v in zip(state_names, values) if not states or name in states]
    return math.sqrt(sum(v * v for v in chosen))


def judge(reference, result):
    """(outcome, detail): outcome one of pass, fail, wrong."""
    if result is None:
        return "fail", "no such run in runs.txt"
    data = result["data"]
    if data is None:
        return "fail", "run failed (exit %s), no JSON" % result["code"]
    if data.get("parameter") not in (None, reference["parameter"]):
        return "fail", "the run continues %s, not %s" % (data.get("parameter"),
                                                          reference["parameter"])
    wanted = KIND_TO_EVENT[reference["kind"]]
    events = [e for e in data.get("events", []) if e.get("type") == wanted]
    if isinstance(data.get("first"), str):
        # A two-parameter curve (curve --json): an event's value is that of the reference's
        # parameter, one of the curve's two, and its period its point's.
        if reference["parameter"] not in (data["first"], data["second"]):
            return "fail", "the curve is in %s and %s, not %s" % (
                data["first"], data["second"], reference["parameter"])
        which = "first" if reference["parameter"] == data["first"] else "second"
        events = [dict(e, value=e[which], period=e.get("point", {}).get("period"),
                       trusted=e.get("located", False)) for e in events]
    if not events:
        stop = data.get("stop_reason", data.get("stop", ""))
        return "fail", "no %s event (run stopped: %s)" % (wanted, stop)

    def distance(event):
        d = abs(event["value"] - reference["value"]) / reference["precision"]
        if reference["period"] is not None and event.get("period") is not None:
            d += abs(event["period"] - reference["period"]) / reference["period_precision"]
        return d

    names = data.get("state_names", [])

    # The nearest, a trusted one first among those within the precision (a two-way run's two
    # stops at the same value, one of them interpolated where its orbit did not correct).
    event = min(events, key=lambda e: (distance(e) > 1.0, not event_trusted(e), distance(e)))
    dv = event["value"] - reference["value"]
    text = "%s at %.10g" % (wanted, event["value"])
    period_ok = True
    if reference["period"] is not None:
        if event.get("period") is None:
            period_ok = False
            text += ", no period"
        else:
            dT = event["period"] - reference["period"]
            text += ", T %.10g (dT %.2g)" % (event["period"], dT)
            period_ok = abs(dT) <= reference["period_precision"]
    if reference["norm"] is not None:
        norm = event_norm(event, names, reference["norm_of"])
        if norm is None:
            period_ok = False
            text += ", no rms in the JSON"
        else:
            dn = norm - reference["norm"]
            text += ", L2 %.10g (d %.2g)" % (norm, dn)
            period_ok = period_ok and abs(dn) <= reference["norm_precision"]
    for extreme in reference["extremes"]:
        values = event.get(extreme["which"])
        if values is None or extreme["name"] not in names:
            period_ok = False
            text += ", no %s of %s" % (extreme["which"], extreme["name"])
            continue
        got = values[names.index(extreme["name"])]
        dx = got - extreme["value"]
        text += ", %s %s %.10g (d %.2g)" % (extreme["which"], extreme["name"], got, dx)
        period_ok = period_ok and abs(dx) <= extreme["precision"]
    text += " (d %.2g, precision %.2g)" % (dv, reference["precision"])
    value_ok = abs(dv) <= reference["precision"]
    trusted = event_trusted(event)
    if value_ok and period_ok:
        if trusted:
            return "pass", text
        return "fail", text + " not trusted" + (": " + event["note"] if event.get("note") else "")
    window = max(100 * reference["precision"], 1e-3 * abs(reference["value"]))
    if abs(dv) <= window and trusted:
        return "wrong", text + " trusted, outside the precision"
    return "fail", "no %s within the precision; nearest %s%s" % (
        wanted, text, "" if trusted else " (not trusted)")


def main(argv):
    args = [a for a in argv[1:]]
    demos, keep, verbose = [], None, False
    positional = []
    i = 0
    while i < len(args):
        if args[i] == "--demo" and i + 1 < len(args):
            demos.append(args[i + 1])
            i += 2
        elif args[i] == "--keep" and i + 1 < len(args):
            keep = args[i + 1]
            i += 2
        elif args[i] == "--verbose":
            verbose = True
            i += 1
        elif args[i].startswith("--"):
            usage("unknown option %s" % args[i])
        else:
            positional.append(args[i])
            i += 1
    if len(positional) != 2:
        usage("expected SYMPATHY and SOURCE_DIR")
    sympathy, source_dir = os.path.abspath(positional[0]), os.path.abspath(positional[1])
    if not os.access(sympathy, os.X_OK):
        usage("%s is not an executable" % sympathy)

    runs = read_runs(os.path.join(HERE, "runs.txt"))
    references = read_references(os.path.join(HERE, "references.csv"))
    if demos:
        runs = [r for r in runs if r["demo"] in demos]
        references = [r for r in references if r["demo"] in demos]
    run_keys = {(r["demo"], r["run"]) for r in runs}

    start = time.monotonic()
    cache = tempfile.mkdtemp(prefix="sympathy-auto-cache-")  # mode 0700
    work = keep or tempfile.mkdtemp(prefix="sympathy-auto-")
    os.makedirs(work, exist_ok=True)
    os.environ["SYMPATHY_CACHE_DIR"] = cache
    try:
        results = run_all(sympathy, source_dir, runs, work, verbose)
    finally:
        shutil.rmtree(cache, ignore_errors=True)
        if keep is None:
            shutil.rmtree(work, ignore_errors=True)
    seconds = time.monotonic() - start

    counts = {"PASS": 0, "FAIL": 0, "WRONG": 0, "XFAIL": 0, "XPASS": 0}
    errors = 0
    for reference in references:
        key = (reference["demo"], reference["run"])
        outcome, detail = judge(reference, results.get(key) if key in run_keys else None)
        if reference["status"] == "pass":
            label = {"pass": "PASS", "fail": "FAIL", "wrong": "WRONG"}[outcome]
            error = outcome != "pass"
        else:
            label = "XPASS" if outcome == "pass" else "XFAIL"
            error = outcome == "pass"
        counts[label] += 1
        errors += error
        what = "%s %s %s=%s" % (reference["demo"], reference["run"], reference["kind"],
                                "%.10g" % reference["value"])
        if reference["period"] is not None:
            what += " T=%.10g" % reference["period"]
        line = "%-5s %-44s %s" % (label, what, detail)
        if label == "XFAIL":
            line += "  [xfail: %s]" % reference["reason"]
        if label == "XPASS":
            line += "  [marked xfail (%s): flip it to pass in references.csv]" % reference["reason"]
        if label == "WRONG":
            line += "  [a trusted value outside the precision]"
        print(line)
    print("auto demos: %d references, %d passed, %d expected failures, %d failed, %d wrong, "
          "%d unexpectedly passed; %d runs in %.1f s" % (
              len(references), counts["PASS"], counts["XFAIL"], counts["FAIL"], counts["WRONG"],
              counts["XPASS"], len(runs), seconds))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
