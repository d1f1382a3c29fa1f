"""Results as objects: their fields as attributes (as the engine and the JSON name them),
``to_dict()`` for plain Python containers, and ``to_dataframe()`` of a branch's or curve's points
(one row a point) where pandas is installed."""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

import numpy as np


def _plain(value: Any) -> Any:
    if isinstance(value, SimpleNamespace):
        return {k: _plain(v) for k, v in vars(value).items()}
    if isinstance(value, dict):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


class Result(SimpleNamespace):
    """A result of sympathy's: its fields as attributes."""

    def to_dict(self) -> dict:
        """The result as plain Python containers (dicts, lists, numbers, strings): what
        ``json.dumps`` takes, but for complex multipliers."""
        return _plain(self)

    def to_dataframe(self) -> Any:
        """The points as a pandas DataFrame, one row a point (a result without points: its
        fields as one row). ImportError where pandas is not installed."""
        points = getattr(self, "points", None)
        if isinstance(points, Points):
            return points.to_dataframe()
        return Points(**{k: np.asarray([v]) for k, v in vars(self).items()
                         if np.isscalar(v)}).to_dataframe()


    def plot(self, ax: Any = None, out: Any = None, **options: Any) -> Any:
        """The result's figure (a branch of orbits or equilibria, a curve, a simulation) by
        ``sympathy.plot.draw``: on `ax` or a new figure of a journal column's size, written to
        `out` if given (PDF, SVG or PNG by its extension); returns the axes. Options: ``y`` for
        a branch (a state's name, "period", "frequency", "phase:th2"), ``states`` for a
        simulation."""
        from . import plot
        return plot.draw(self, ax, out, **options)


class Points(Result):
    """A branch's or curve's points: each field an array along them (a row a point)."""

    def columns(self) -> dict[str, np.ndarray]:
        """One 1-D array per column: a 2-D field's columns as NAME[j], a dict's as NAME.LABEL."""
        out: dict[str, np.ndarray] = {}
        for name, value in vars(self).items():
            if isinstance(value, dict):
                for label, v in value.items():
                    out[f"{name}.{label}"] = np.asarray(v)
                continue
            a = np.asarray(value)
            if a.ndim == 1:
                out[name] = a
            elif a.ndim == 2:
                for j in range(a.shape[1]):
                    out[f"{name}[{j}]"] = a[:, j]
        return out

    def to_dataframe(self) -> Any:
        try:
            import pandas
        except ImportError:
            raise ImportError("to_dataframe needs pandas (apt-get install python3-pandas, or "
                              "pip install pandas); to_dict() and the arrays need nothing") from None
        return pandas.DataFrame(self.columns())


def wrap(value: Any, name: str = "") -> Any:
    """The engine's or a JSON's result with its namespaces as Results (Points for points)."""
    if isinstance(value, SimpleNamespace):
        fields = {k: wrap(v, k) for k, v in vars(value).items()}
        return Points(**fields) if name == "points" else Result(**fields)
    if isinstance(value, dict):
        return {k: wrap(v) for k, v in value.items()}
    if isinstance(value, list):
        return [wrap(v) for v in value]
    return value
