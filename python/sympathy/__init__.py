"""Periodic orbits, their Floquet multipliers, branches and bifurcations: sympathy from Python.

A case file of either kind (or a dict of its contents) is a :class:`Case`; the commands
``simulate``, ``orbit``, ``continue`` (:func:`continue_branch`), ``curve``, ``equilibria``, ``fit``
and ``study`` are functions of the same names, and methods of a Case, run on the same code as the
program. Their keywords are the command's options (``max_step=0.05`` for ``--max-step 0.05``;
``from_`` for ``--from``), typed: ``inspect.signature`` and ``help()`` list them with their types,
and each is checked before any work (``TypeError`` for a wrong type, :class:`InputError` for a bad
value, naming the keyword). Results are objects (:class:`Result`) whose fields are NumPy arrays,
numbers and strings, with ``to_dict()``, and ``to_dataframe()`` of their points where pandas is
installed; :func:`load` reads back any JSON the program writes.
"""

from __future__ import annotations

import functools
import inspect
import os
from collections.abc import Mapping
from typing import Any, Optional, Union

from . import _core, _options, _results
from ._core import InputError, OutputError
from ._load import load as _load
from ._results import Points, Result

# Raised as sympathy.InputError (a ValueError) and sympathy.OutputError (an OSError).
InputError.__module__ = OutputError.__module__ = __name__

# Not `map`: `from sympathy import *` would hide Python's own (sympathy.map is the command).
__all__ = ["Case", "InputError", "OutputError", "Result", "Points", "simulate", "orbit",
           "continue_branch", "curve", "equilibria", "fit", "study", "basins", "sweep", "load"]

# Each function: the command it runs, what it does (the first line of its docstring), and whether
# it reports progress.
_FUNCTIONS = {
    "simulate": ("simulate", "sympathy simulate: t and states (NumPy arrays) from a start.",
                 False),
    "orbit": ("orbit", "sympathy orbit: a periodic orbit with its Floquet multipliers, their "
              "kinds, its stability and accuracy.", False),
    "continue_branch": ("continue", "sympathy continue: a branch of periodic orbits, its points "
                        "as NumPy arrays and its events as objects; Ctrl-C returns the points so "
                        "far, stop 'interrupted'.", True),
    "equilibria": ("equilibria", "sympathy equilibria: a branch of equilibria with its LP, BP "
                   "and HB points.", True),
    "fit": ("fit", "sympathy fit: parameters and initial values fitted to a recording.", False),
    "curve": ("curve", "sympathy curve: the two-parameter curve of a branch's event (the branch "
              "as continue_branch computes it: result.branch).", True),
}

CaseSource = Union[str, os.PathLike, Mapping[str, Any]]


class Case:
    """A case file (metronome or equation case file; a path, or a dict of its contents) with a
    parameter set and values set on top (``set={'k': 20.0}``)."""

    def __init__(self, source: CaseSource, params: Optional[str] = None,
                 set: Optional[Mapping[str, float]] = None) -> None:
        if params is not None and not isinstance(params, str):
            raise TypeError(f"Case(): params must be a str, not {type(params).__name__}")
        values = _options.checked("Case", {"kind": "assignments", "keyword": "set"},
                                  set) if set is not None else None
        if not isinstance(source, Mapping):
            source = os.fspath(source)
        self._core = _core.Case(source if not isinstance(source, Mapping) else dict(source),
                                params, values)

    @property
    def path(self) -> str:
        """The case file (for a dict, the file written from it)."""
        return self._core.path

    @property
    def params(self) -> str:
        """The parameter set applied."""
        return self._core.params

    @property
    def parameters(self) -> dict[str, float]:
        """Every parameter's value, by name."""
        return self._core.parameters

    @property
    def state_names(self) -> list[str]:
        """The states' names, in the order of the states' arrays."""
        return self._core.state_names

    def with_values(self, **values: float) -> "Case":
        """The same case with these parameter values set on top (``k=20.0``)."""
        checked = _options.checked("with_values", {"kind": "assignments", "keyword": "values"},
                                   values)
        c = Case.__new__(Case)
        c._core = self._core.with_values(checked)
        return c

    def __repr__(self) -> str:
        return f"sympathy.Case({self.path!r}, params={self.params!r})"


def _as_case(case: Union[Case, CaseSource]) -> Case:
    return case if isinstance(case, Case) else Case(case)


def _function(name: str, method: bool) -> Any:
    command, summary, progress = _FUNCTIONS[name]
    first = [inspect.Parameter("self" if method else "case",
                               inspect.Parameter.POSITIONAL_ONLY,
                               annotation=Case if method else Union[Case, CaseSource])]
    sig = _options.signature(command, first, progress, Any)
    where = f"Case.{name}" if method else name

    def call(*args: Any, **kwargs: Any) -> Any:
        bound = _options.keywords(where, sig, args, kwargs)
        case = _as_case(bound.arguments["self" if method else "case"])
        given = _options.engine_keywords(where, command, bound)
        run = getattr(case._core, name)
        if progress:
            return _results.wrap(run(given, bound.arguments.get("progress")))
        return _results.wrap(run(given))

    call.__name__ = name
    call.__qualname__ = where
    call.__doc__ = _options.docstring(command, summary, progress)
    call.__signature__ = sig  # type: ignore[attr-defined]
    call.__module__ = __name__
    return call


for _name in _FUNCTIONS:
    setattr(Case, _name, _function(_name, method=True))
    globals()[_name] = _function(_name, method=False)


def _file_function(command: str, summary: str) -> Any:
    """A command whose argument is a file of its own (a study file, a map file, a case file or
    basins study file for basins)."""
    first = [inspect.Parameter("path", inspect.Parameter.POSITIONAL_ONLY,
                               annotation=Union[str, os.PathLike])]
    sig = _options.signature(command, first, True, Any, jobs=True)
    run = getattr(_core, command)

    def call(*args: Any, **kwargs: Any) -> Any:
        bound = _options.keywords(command, sig, args, kwargs)
        path = os.fspath(bound.arguments["path"])
        result = run(path, _options.engine_keywords(command, command, bound),
                     bound.arguments.get("progress"))
        if command in ("basins", "sweep"):  # its JSON is the result, as load reads it
            json_path, interrupted = result
            result = _load(json_path)
            result.interrupted = interrupted
        return _results.wrap(result)

    call.__name__ = call.__qualname__ = command
    call.__doc__ = _options.docstring(command, summary, True, jobs=True)
    call.__signature__ = sig  # type: ignore[attr-defined]
    call.__module__ = __name__
    return call


study = _file_function("study", (
    "sympathy study: the branches and equilibria entries of a study file "
    "(``cases/figures/*.toml``) side by side, their CSV files written to out as the program "
    "writes them; a namespace with title, parameter, branches (a dict by name, each as "
    "continue_branch returns it, with error: why it has none, or '') and equilibria (a dict by "
    "name, each as equilibria returns it, with error), equilibria_axis (the state their diagram "
    "is drawn in), basins (a [basins] table's walk: values, shares by attractor, attractors, "
    "fates, runs and changes, or None). Ctrl-C returns the branches so far."))
map = _file_function("map", (
    "sympathy map: where each orbit of a map file (``cases/figures/map_*.toml``) is stable in two "
    "parameters: its branch, the curve of every event on it in both parameters and its stability "
    "on a grid, and each equilibria entry's branch with the fold and Hopf curves of its events, "
    "the JSON and CSV files written to out; a namespace with name, title, first, second, window, "
    "json (the JSON's path), orbits (each with name, branch, curves, grid: first, second, "
    "unstable_count, or None, error) and equilibria (each with name, start, branch, curves, "
    "error). Ctrl-C returns what was computed."))
basins = _file_function("basins", (
    "sympathy basins: how often each synchronized state wins from random starts over a grid of "
    "one or two parameters, on this machine's threads (under mpirun, use the program), the files "
    "written to out as the program writes them (a journal that resume=True continues); the JSON "
    "as load reads it: per grid point its values, runs and each state's share with its 95% "
    "Wilson interval, and interrupted (Ctrl-C returns what was done)."))
sweep = _file_function("sweep", (
    "sympathy sweep: a branch (param=, from_=, to=), an orbit (neither), or a fit (data=) at each "
    "value of a second parameter (over='NAME=FROM:TO:COUNT'), on this machine's threads (under "
    "mpirun, use the program), the files written to out as the program writes them (a journal "
    "that resume=True continues); the JSON as load reads it (kind sweep: branches, orbits or "
    "fits, one per value), and interrupted (Ctrl-C returns what was done)."))
del _name


def load(path: Union[str, os.PathLike]) -> Result:
    return _results.wrap(_load(path))


load.__doc__ = _load.__doc__
