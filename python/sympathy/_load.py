"""sympathy.load: any JSON the program writes, read back as the functions return their results.

AUTO's ``load``: an orbit (``orbit --json``), a branch (``continue --json``), a curve
(``curve --json``), equilibria (``equilibria --json``), a study's, a map's, basins' or a sweep's
JSON, as one object
whose ``kind`` says which, with the JSON's keys as attributes: points along a branch or curve as
NumPy arrays by key (multipliers and eigenvalues complex, one row a point), events as objects,
a study's branches and equilibria entries as dicts by name, a map's orbits and equilibria entries
as lists.
"""

from __future__ import annotations

import json
import os
from types import SimpleNamespace
from typing import Any, Union

import numpy as np

from ._core import InputError

# Keys whose values are lists of [re, im] pairs.
_COMPLEX = ("multipliers", "eigenvalues")


def _complex(value: Any) -> Any:
    a = np.asarray(value, dtype=float)
    return a[..., 0] + 1j * a[..., 1] if a.ndim >= 1 and a.shape[-1:] == (2,) else a


def _array(key: str, values: list) -> Any:
    """A key's values along the points: an array where they make one, else the list."""
    try:
        if key in _COMPLEX:
            return _complex(values)
        if all(isinstance(v, dict) for v in values):  # the describer's groups, by label
            return {k: np.asarray([v[k] for v in values]) for k in values[0]} if values else {}
        a = np.asarray(values)
        return a if a.dtype != object else values
    except (ValueError, TypeError, KeyError):
        return values


def _points(points: list) -> SimpleNamespace:
    keys = list(points[0].keys()) if points else []
    return SimpleNamespace(**{k: _array(k, [p.get(k) for p in points]) for k in keys})


def _object(j: dict) -> SimpleNamespace:
    """A JSON object with its events, points, branches and curves converted."""
    out = {}
    for k, v in j.items():
        if k == "points" and isinstance(v, list):
            out[k] = _points(v)
        elif k in ("events",) and isinstance(v, list):
            out[k] = [_object(e) for e in v]
        elif k in ("branch",) and isinstance(v, dict):
            out[k] = _object(v)
        elif k in ("curves", "orbits", "branches", "equilibria") and isinstance(v, list):
            out[k] = [_object(x) for x in v]
        elif k in _COMPLEX and isinstance(v, list):
            out[k] = _complex(v)
        elif k == "hopf" and isinstance(v, dict):
            out[k] = SimpleNamespace(**v)
        else:
            out[k] = v
    return SimpleNamespace(**out)


def kind_of(j: Any) -> str:
    """Which JSON of the program's this is ("" for none)."""
    if not isinstance(j, dict):
        return ""
    if "map" in j and "orbits" in j:
        return "map"
    if "study" in j and "branches" in j and "over" not in j:
        return "study"
    if j.get("kind") == "equilibria":
        return "equilibria"
    if "points" in j and "first" in j and "second" in j and "kind" in j:
        return "curve"
    if "points" in j and "parameter" in j and "events" in j:
        return "branch"
    if "multipliers" in j and "period" in j and "state0" in j:
        return "orbit"
    if "runs_csv" in j and "points" in j and "grid" in j:
        return "basins"
    if "over" in j and "complete" in j and any(k in j for k in ("branches", "orbits", "fits")):
        return "sweep"
    return ""


def _walk(j: dict) -> SimpleNamespace:
    """A study's [basins] walk: values (an array), shares (a dict by attractor: branch, and
    count, share, lower, upper, certified_q1, certified_median, certified_q3 as arrays over the
    values, NaN where no run was certified), attractors (per value, each with name, branch,
    point, period, max_multiplier, state), fates and runs per value, changes (each with name,
    appears, before, after, present_before, present_after, events)."""
    def array(key: str, v: Any) -> Any:
        if not isinstance(v, list):
            return v
        return np.asarray(v, dtype=float) if key.startswith("certified_") else np.asarray(v)

    shares = {s["name"]: SimpleNamespace(**{k: array(k, v) for k, v in s.items()})
              for s in j["shares"]}
    attractors = [[SimpleNamespace(**a) for a in value] for value in j["attractors"]]
    changes = [SimpleNamespace(**{**c, "events": [SimpleNamespace(**e) for e in c["events"]]})
               for c in j["changes"]]
    return SimpleNamespace(**{**j, "values": np.asarray(j["values"]), "shares": shares,
                              "attractors": attractors, "changes": changes})


def _basins(j: dict) -> SimpleNamespace:
    """A basins JSON: per grid point its values (a dict by parameter), runs and each state's
    share (a dict by state: count, share and its 95% Wilson interval lower, upper)."""
    points = [SimpleNamespace(**{**p, "shares": {state: SimpleNamespace(**v)
                                                 for state, v in p["shares"].items()}})
              for p in j["points"]]
    return SimpleNamespace(**{**j, "points": points})


def load(path: Union[str, "os.PathLike[str]"]) -> SimpleNamespace:
    """Any JSON the program writes (orbit, branch, curve, equilibria, study, map) as an object:
    ``kind`` says which, the JSON's keys are its attributes, points are NumPy arrays by key.
    ``sympathy.InputError`` naming the file for anything else."""
    path = os.fspath(path)
    try:
        with open(path) as f:
            j = json.load(f)
    except OSError as e:
        raise InputError(f"{path}: cannot be read ({e.strerror})") from None
    except json.JSONDecodeError as e:
        raise InputError(f"{path}:{e.lineno}: not JSON ({e.msg})") from None
    kind = kind_of(j)
    if not kind:
        raise InputError(f"{path}: expected a JSON the program writes (an orbit, a branch, a "
                         "curve, equilibria, a study, a map, basins or a sweep)")
    result = _basins(j) if kind == "basins" else _object(j)
    if kind == "study":  # by name, as sympathy.study returns them
        result.branches = {b.name: b for b in result.branches}
        result.equilibria = {e.name: e for e in getattr(result, "equilibria", [])}
        result.basins = _walk(j["basins"]) if "basins" in j else None
    result.kind = kind
    result.path = path
    return result
