"""Figures of sympathy's results, for any system: one module that ``Result.plot()`` and the
plotting scripts call. A branch of orbits or equilibria is drawn stable solid black and unstable
dashed grey, the style changing at the located event (not at the last point computed before it);
its events are marked and named, their labels placed so that no two overlap; a study's branches
on one diagram; a two-parameter curve in its two parameters with its codimension-two points; a
stability map's regions, curves and parameter sets; basins (the shares of the states over one
parameter, with a study's diagram below, maps of them over two, one grid point's starts); a
simulation's states against time; a fit; the bench's accuracy report. Sizes are those of a
journal's column (3.4 inches wide, 8-point text), a page's (7 inches) for the figures of several
panels; ``save`` writes PDF, SVG or PNG by the file's extension.

    >>> import sympathy, sympathy.plot
    >>> branch = sympathy.continue_branch("cases/row2.toml", start="in-phase", param="k",
    ...                                   from_=1, to=100)
    >>> ax = branch.plot()                       # on a new figure
    >>> sympathy.plot.save(ax.figure, "in_phase.pdf")
"""

from __future__ import annotations

import math
from typing import Any, Callable, Optional, Union

import numpy as np

COLUMN = (3.4, 2.4)  # inches: a journal's column
STABLE = dict(color="black", lw=1.4, ls="-")
UNSTABLE = dict(color="0.55", lw=1.2, ls="--")
EVENT_COLOR = "tab:red"
MARKERS = {"LP": "s", "BP": "o", "PD": "^", "NS": "D", "HB": "*", "UZ": "x", "TR": "v",
           "CP": "P", "BT": "X", "GH": "h"}
# Units of the metronome model's parameters, for axis labels (an equation case file's have none).
UNITS = {"M": "kg", "c": "N s/m", "k": "N/m", "kappa": "N m/rad", "d": "N m s", "s": "N m",
         "mp": "kg", "mb": "kg", "lp": "m", "lb": "m"}
# State names drawn as mathematics: th2 -> theta_2, vx -> v_x.
_GREEK = {"th": r"\theta", "ph": r"\phi", "om": r"\omega"}


def math_name(name: str) -> str:
    """A state's or parameter's name as mathtext where it reads as one (th2: theta_2)."""
    for short, symbol in _GREEK.items():
        if name.startswith(short) and name[len(short):].isdigit():
            return f"${symbol}_{{{name[len(short):]}}}$"
    if len(name) == 2 and name[0] == "v" and name[1].isalpha():
        return f"$v_{{{name[1]}}}$"
    if len(name) > 1 and name[0].isalpha() and name[1:].isdigit():
        return f"${name[0]}_{{{name[1:]}}}$"
    return name


def axis_label(name: str) -> str:
    unit = UNITS.get(name.rstrip("0123456789"))
    return f"{math_name(name)} ({unit})" if unit else math_name(name)


def new_axes(ax: Any = None) -> Any:
    """`ax`, or the axes of a new figure of a column's size with 8-point text."""
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt  # type: ignore[import]
    fig, ax = plt.subplots(figsize=COLUMN, layout="constrained")
    return ax


def _finish(ax: Any, legend: bool = True, **legend_options: Any) -> None:
    """A journal column's text sizes (8 pt, the legend 7 pt), whatever matplotlib's defaults."""
    ax.title.set_fontsize(8)
    ax.xaxis.label.set_fontsize(8)
    ax.yaxis.label.set_fontsize(8)
    ax.tick_params(labelsize=8)
    if legend:
        ax.legend(fontsize=7, **legend_options)


def save(fig: Any, path: str, dpi: int = 300) -> None:
    """The figure to `path`, its format by the extension (.pdf, .svg, .png; PNG at `dpi`)."""
    import os
    ext = os.path.splitext(str(path))[1].lower()
    if ext not in (".pdf", ".svg", ".png"):
        raise ValueError(f"{path}: expected a .pdf, .svg or .png file")
    fig.savefig(path, dpi=dpi if ext == ".png" else None)


# What to draw on the vertical axis of a branch: a state's amplitude ("x"), "period",
# "frequency", or a phase difference to the first angle ("phase:th2", |th2 - th1| in rad).
YAxis = Union[str, Callable[[Any], np.ndarray], None]


def _by_name(field: Any, names: list[str]) -> dict[str, np.ndarray]:
    """A per-state field as a dict by name: the functions' results give one; a JSON read back
    (sympathy.load) an array whose columns are the first of `names` in order."""
    if isinstance(field, dict):
        return field
    a = np.asarray(field, dtype=float)
    return {name: a[:, j] for j, name in enumerate(names[:a.shape[1]])}


def _vertical(result: Any, y: YAxis) -> tuple[np.ndarray, str]:
    p = result.points
    names = list(getattr(result, "state_names", []))
    if callable(y):
        return np.asarray(y(p), dtype=float), ""
    if y in ("period", "frequency"):
        values = np.asarray(getattr(p, y), dtype=float)
        return values, "period" if y == "period" else "frequency"
    if y is not None and y.startswith("phase:"):
        state = y.split(":", 1)[1]
        # A metronome model's phase differences: of th2, th3, ... to th1.
        others = [n for n in names if n.startswith("th") and n != "th1"]
        phases = _by_name(p.phase_differences, others)
        return np.abs(np.asarray(phases[state], dtype=float)), \
            f"|{math_name(state)} $-$ {math_name('th1')}| (rad)"
    if hasattr(p, "amplitudes"):  # orbits: a state's amplitude, by default the first's
        amplitudes = _by_name(p.amplitudes, names)
        state = y or next(iter(amplitudes))
        return np.asarray(amplitudes[state], dtype=float), f"amplitude of {math_name(state)}"
    # Equilibria: a state's value, by default the first's.
    state = y or names[0]
    return np.asarray(p.state, dtype=float)[:, names.index(state)], math_name(state)


def _stable(result: Any) -> np.ndarray:
    p = result.points
    if hasattr(p, "stable"):
        return np.asarray(p.stable, dtype=bool)
    return np.asarray(p.unstable) == 0  # equilibria: no eigenvalue in the right half plane


def _position(result: Any) -> Callable[[Any], int]:
    """An event's place in the points' arrays: after the point whose index is its after_point
    (indices are negative on the backward part of a two-way run)."""
    indices = getattr(result.points, "index", None)
    if indices is None:
        return lambda e: int(e.after_point)
    where = {int(i): k for k, i in enumerate(np.asarray(indices))}
    return lambda e: where.get(int(e.after_point), int(e.after_point))


def _at(x: np.ndarray, y: np.ndarray, i: int, value: float) -> float:
    """y where the parameter is `value` between points i and i + 1 (linear)."""
    if i + 1 >= len(x) or x[i + 1] == x[i]:
        return float(y[min(i, len(y) - 1)])
    f = min(max((value - x[i]) / (x[i + 1] - x[i]), 0.0), 1.0)
    return float(y[i] + f * (y[i + 1] - y[i]))


def stability_runs(result: Any, y: YAxis = None) -> list[tuple[bool, np.ndarray, np.ndarray]]:
    """The branch as runs of one stability: (stable, x, y) each. Where stability changes between
    two points, both runs end at the first event located between them (an unlocated change: half
    way)."""
    return _runs(result, np.asarray(result.points.value, dtype=float), _vertical(result, y)[0])


def _runs(result: Any, x: np.ndarray, yy: np.ndarray) -> list[tuple[bool, np.ndarray, np.ndarray]]:
    """stability_runs on the branch's parameter values `x` and vertical values `yy`."""
    stable = _stable(result)
    between: dict[int, float] = {}
    position = _position(result)
    for e in sorted(result.events, key=lambda e: e.value):
        if e.type != "UZ":
            between.setdefault(position(e), float(e.value))
    runs = []
    xs, ys = [x[0]], [yy[0]]
    for i in range(len(x) - 1):
        if stable[i + 1] == stable[i]:
            xs.append(x[i + 1])
            ys.append(yy[i + 1])
            continue
        at = between.get(i, 0.5 * (x[i] + x[i + 1]))
        y_at = _at(x, yy, i, at)
        xs.append(at)
        ys.append(y_at)
        runs.append((bool(stable[i]), np.asarray(xs), np.asarray(ys)))
        xs, ys = [at, x[i + 1]], [y_at, yy[i + 1]]
    runs.append((bool(stable[-1]), np.asarray(xs), np.asarray(ys)))
    return runs


def _line_points(ax: Any, spacing: float = 2.0) -> np.ndarray:
    """The drawn lines of `ax` (branches, curves, marks' vertical lines; not the events' markers
    nor the leader lines) as points in display coordinates, at most `spacing` pixels apart."""
    points = [np.zeros((0, 2))]
    for line in ax.get_lines():
        if str(line.get_gid()).startswith("event ") or line.get_linestyle() in ("None", "none", ""):
            continue
        xy = line.get_transform().transform(np.column_stack([line.get_xdata(),
                                                             line.get_ydata()]))
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        for (x0, y0), (x1, y1) in zip(xy[:-1], xy[1:]):
            n = int(max(abs(x1 - x0), abs(y1 - y0)) / spacing) + 1
            f = np.linspace(0.0, 1.0, n + 1)[:, None]
            points.append(np.column_stack([x0 + f[:, 0] * (x1 - x0), y0 + f[:, 0] * (y1 - y0)]))
    return np.concatenate(points)


def place_labels(ax: Any, labels: list, within: Any = None, clear_of: Any = (),
                 reach: Optional[int] = 10) -> list:
    """Moves annotations (in the order given) until no two overlap, none covers an event's
    marker, the legend or a box of `clear_of`, and each lies inside the axes (or the figure,
    `within="figure"`): each tries offsets above and below its point and on its left, nearer
    first, up to `reach` label heights away (None: as far as `within` goes), and takes the
    nearest that crosses no drawn line (else the nearest that is free of
    the rest). A label moved away from its marker gets a thin leader line to it, which later
    labels keep clear of. Returns the boxes the labels took (for a later call's `clear_of`)."""
    fig = ax.figure
    # Extents are known once drawn (the layout done); the layout is then kept, so that the places
    # found hold in the file.
    fig.canvas.draw()
    if hasattr(fig, "set_layout_engine"):
        fig.set_layout_engine("none")
    renderer = fig.canvas.get_renderer()
    inside = fig.bbox if within == "figure" else ax.get_window_extent(renderer)
    boxes = [[b.x0, b.y0, b.x1, b.y1] for b in clear_of]
    taken: list = []
    legend = ax.get_legend()
    if legend is not None:
        b = legend.get_window_extent(renderer)
        boxes.append([b.x0, b.y0, b.x1, b.y1])
        # Kept where it is: a legend at "best" would otherwise move over the labels placed now.
        corner = ax.transAxes.inverted().transform((b.x0, b.y0))
        if legend.get_bbox_to_anchor().bounds == ax.bbox.bounds:
            legend._loc = (float(corner[0]), float(corner[1]))
    # The events' markers too: a label does not cover another event.
    for line in ax.get_lines():
        if str(line.get_gid()).startswith("event "):
            # The marker's half size and its edge's width (a label's first letter was hidden
            # under a neighbouring codimension-two point's circle by the size alone).
            r = (line.get_markersize() / 2.0 + line.get_markeredgewidth()) * fig.dpi / 72.0
            for px, py in ax.transData.transform(np.column_stack([line.get_xdata(),
                                                                  line.get_ydata()])):
                boxes.append([px - r, py - r, px + r, py + r])
    lines = _line_points(ax)

    def free(box: Any) -> tuple[bool, bool]:
        """(clear of every box and inside, clear of the drawn lines too)"""
        if box.x0 < inside.x0 or box.x1 > inside.x1 or box.y0 < inside.y0 or box.y1 > inside.y1:
            return False, False
        if boxes:
            o = np.asarray(boxes)
            if np.any((o[:, 0] < box.x1) & (o[:, 2] > box.x0) & (o[:, 1] < box.y1) &
                      (o[:, 3] > box.y0)):
                return False, False
        crossed = np.any((lines[:, 0] > box.x0) & (lines[:, 0] < box.x1) &
                         (lines[:, 1] > box.y0) & (lines[:, 1] < box.y1))
        return True, not crossed

    from matplotlib.transforms import Bbox  # type: ignore[import]
    for label in labels:
        x0, y0 = label.xyann
        height = label.get_window_extent(renderer).height * 72.0 / fig.dpi + 1.0
        width = label.get_window_extent(renderer).width * 72.0 / fig.dpi
        # Places nearer first: up or down a label's height at a time, or on the marker's left
        # (as far as a label's width); within `reach` first, then as far as `within` goes (a
        # label left where it was when nothing near was free overlapped a neighbour's).
        everywhere = int(inside.height * 72.0 / fig.dpi / height) + 1
        steps = max(everywhere, reach or 0)
        candidates = sorted(((side, step) for side in (0, 1) for step in range(-steps, steps + 1)),
                            key=lambda c: abs(c[1]) * height + c[0] * (width + 6.0) +
                            (0.5 if c[1] < 0 else 0.0))
        found: dict = {}  # (near, clear of the lines) -> the first such place
        for side, step in candidates:
            label.xyann = (x0 if side == 0 else -x0 - width, y0 + step * height)
            box = label.get_window_extent(renderer)
            clear, clear_of_lines = free(box)
            near = reach is None or abs(step) <= reach
            if clear:
                found.setdefault((near, clear_of_lines), (label.xyann, box))
                if near and clear_of_lines:
                    break
        choice = next((found[k] for k in ((True, True), (True, False), (False, True),
                                          (False, False)) if k in found), None)
        if choice is None:  # nowhere free: where it was, still drawn
            label.xyann = (x0, y0)
            choice = (label.xyann, label.get_window_extent(renderer))
        label.xyann = choice[0]
        box = choice[1]
        boxes.append([box.x0, box.y0, box.x1, box.y1])
        taken.append(Bbox([[box.x0, box.y0], [box.x1, box.y1]]))
        if label.xyann != (x0, y0) and label.get_gid() != "mark label":
            # Moved away from its marker: a thin leader line to it.
            ax.annotate("", label.xy, textcoords="offset points", xytext=label.xyann,
                        gid="leader", arrowprops=dict(arrowstyle="-", lw=0.4,
                                                      color=label.get_color(), shrinkA=0,
                                                      shrinkB=2))
            # Later labels keep clear of it: its points as tiny boxes.
            start = ax.transData.transform(label.xy) if label.xycoords == "data" else None
            if start is not None:
                end = np.array([box.x0 if label.xyann[0] >= 0 else box.x1, box.y0])
                n = int(np.hypot(*(end - start)) / 3.0) + 1
                for f in np.linspace(0.0, 1.0, n + 1)[1:-1]:
                    px, py = start + f * (end - start)
                    boxes.append([px - 0.5, py - 0.5, px + 0.5, py + 0.5])
    return taken


def _events(ax: Any, events: list, where: Callable[[Any], tuple[float, float]],
            value: Callable[[Any], float] = lambda e: e.value,
            seen: Optional[set] = None) -> list:
    """Each event marked (its type's marker) and named with its parameter's `value` (a legend
    entry per type once: `seen`); returns the labels, for place_labels."""
    labels = []
    drawn: set = seen if seen is not None else set()
    for e in sorted(events, key=value):
        x, y = where(e)
        kind = e.type
        ax.plot([x], [y], marker=MARKERS.get(kind, "x"), color=EVENT_COLOR, ms=4, ls="none",
                zorder=5, label=None if kind in drawn else kind, gid=f"event {kind}")
        drawn.add(kind)
        trusted = getattr(e, "trusted", True)
        labels.append(ax.annotate(f"{kind}{'' if trusted else '?'} {value(e):.4g}", (x, y),
                                  textcoords="offset points", xytext=(3, 3), fontsize=6.5,
                                  color=EVENT_COLOR, gid="event label"))
    return labels


def _draw_branch(ax: Any, result: Any, y: YAxis, label: Optional[str],
                 seen: set) -> tuple[list, Any]:
    """The branch's runs and events on `ax` (legend entries once per kind: `seen`); returns its
    event labels and its name's label at its end (None without `label`), placed by the caller."""
    x = np.asarray(result.points.value, dtype=float)
    yy, _ = _vertical(result, y)
    for stable, xs, ys in _runs(result, x, yy):
        name = "stable" if stable else "unstable"
        ax.plot(xs, ys, **(STABLE if stable else UNSTABLE), gid=name,
                label=None if name in seen else name)
        seen.add(name)
    position = _position(result)
    labels = _events(ax, list(result.events),
                     lambda e: (e.value, _at(x, yy, position(e), e.value)), seen=seen)
    tag = None
    if label:  # the branch's name at its end (placed first, outside the axes if need be)
        tag = ax.annotate(label, (x[-1], yy[-1]), textcoords="offset points", xytext=(3, 0),
                          fontsize=7, gid="branch label")
    return labels, tag


def branch(result: Any, ax: Any = None, y: YAxis = None, label: Optional[str] = None) -> Any:
    """A branch of periodic orbits or of equilibria: stable solid, unstable dashed, the style
    changing at the located events, the events marked and named. `y`: a state's amplitude (or for
    equilibria its value) by name, "period", "frequency", "phase:th2", or a function of the
    points. Returns the axes."""
    ax = new_axes(ax)
    labels, tag = _draw_branch(ax, result, y, label, set())
    ax.set_xlabel(axis_label(result.parameter))
    ax.set_ylabel(_vertical(result, y)[1])
    _finish(ax, loc="best")
    place_labels(ax, labels, clear_of=place_labels(ax, [tag] if tag else [], within="figure"))
    return ax


def _drawn(entries: Any) -> dict:
    """A study's branches or equilibria entries (a dict by name) that have points to draw."""
    return {name: b for name, b in (entries or {}).items()
            if not getattr(b, "error", "") and len(getattr(b.points, "value", [])) > 0}


def study(result: Any, ax: Any = None) -> Any:
    """A study's branches on one diagram, as the paper draws its Figs. 6-9, 12 and 18-20: the
    absolute phase difference of th2 to th1 (0 in phase, pi in anti-phase) or the frequency
    against the study's parameter, each branch named at its end, every event label placed apart
    from all the others. Its equilibria entries (``[[equilibria]]``) in a panel of their own
    below, on the same parameter axis (alone when the study has no branches): the state
    ``equilibria_axis`` names (by default the first) against the parameter, stable solid,
    unstable dashed, their events marked and named as the branches' are. Its basin walk
    (``[basins]``) in a panel above: each attractor's share against the parameter with its 95%
    interval, the located events where a share appears or disappears as dotted lines. Two or
    three panels need a new figure (no `ax`). An equation case file's branches (no pendula) are
    drawn by the maximum of the state whose maximum varies most along them. Returns the (first) axes."""
    equilibria = _drawn(getattr(result, "equilibria", None))
    walk = getattr(result, "basins", None)
    orbits = bool(_drawn(result.branches))
    panels = ([("basins", walk)] if walk is not None and len(walk.values) else []) + \
        ([("orbits", None)] if orbits or not equilibria else []) + \
        ([("equilibria", equilibria)] if equilibria else [])
    if len(panels) == 1 and panels[0][0] == "orbits":
        ax = new_axes(ax)
        _orbits_diagram(result, ax)()
        return ax
    if len(panels) == 1 and panels[0][0] == "equilibria":
        ax = new_axes(ax)
        _equilibria_diagram(ax, result, equilibria, titled=True)()
        return ax
    if ax is not None:
        count = {2: "two", 3: "three"}[len(panels)]
        raise ValueError(f"plot: a study with {' and '.join(k for k, _ in panels)} draws "
                         f"{count} panels; no ax")
    import matplotlib.pyplot as plt  # type: ignore[import]
    fig, axes = plt.subplots(len(panels), 1, sharex=True, layout="constrained",
                             figsize=(COLUMN[0], len(panels) * COLUMN[1] + 0.6))
    # Every panel drawn before any label is placed: place_labels fixes the layout it finds.
    places = []
    for (kind, _), panel in zip(panels, axes):
        if kind == "basins":
            _walk_shares(panel, walk, result.parameter)
        elif kind == "orbits":
            places.append(_orbits_diagram(result, panel))
        else:
            places.append(_equilibria_diagram(panel, result, equilibria, titled=False))
        if panel is not axes[-1]:
            panel.set_xlabel("")
    if panels[0][0] == "basins":  # the title once, above the top panel
        import textwrap
        axes[0].set_title(textwrap.fill(getattr(result, "title", ""), 36))
        axes[1].set_title("")
    for place in places:
        place()
    return axes[0]


def _walk_shares(ax: Any, walk: Any, parameter: str) -> None:
    """A study's basin walk ([basins]) on `ax`: each attractor's share of the starts against the
    parameter, a named curve with its 95% interval (where the share is not zero); where a share appears or disappears,
    the located events between the two values as dotted vertical lines (not where the attractor
    was there all along: that is the starts' sampling)."""
    x = np.asarray(walk.values, dtype=float)
    for name, s in walk.shares.items():
        share = np.asarray(s.share, dtype=float)
        (line,) = ax.plot(x, share, marker="o", ms=3, lw=1.2, label=name, gid=f"share {name}")
        # The intervals where the share is not zero (at zero they would all lie on one another).
        on = share > 0
        ax.errorbar(x[on], share[on], yerr=[share[on] - np.asarray(s.lower)[on],
                                            np.asarray(s.upper)[on] - share[on]],
                    fmt="none", ecolor=line.get_color(), elinewidth=0.7, capsize=2)
    events = sorted({(e.type, e.parameter) for c in walk.changes
                     if not (c.present_before and c.present_after) for e in c.events})
    for kind, value in events:
        ax.axvline(value, color="0.4", ls=":", lw=0.8, gid=f"change {kind}")
    ax.set_ylim(-0.03, 1.03)
    ax.set_ylabel("share of starts")
    ax.set_xlabel(axis_label(parameter))
    _finish(ax, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3, frameon=False,
            handlelength=1.8, columnspacing=1.0)


def _equilibria_diagram(ax: Any, result: Any, equilibria: dict,
                        titled: bool) -> Callable[[], None]:
    """The study's equilibria entries on `ax` (study's lower panel), each named at its end;
    returns what places their labels."""
    names = list(next(iter(equilibria.values())).state_names)
    state = getattr(result, "equilibria_axis", "") or names[0]
    seen: set = set()
    labels: list = []
    tags: list = []
    for name, e in equilibria.items():
        events, tag = _draw_branch(ax, e, state, name, seen)
        labels += events
        tags.append(tag)
    ax.set_xlabel(axis_label(result.parameter))
    ax.set_ylabel(f"{math_name(state)} (equilibria)")
    title = str(getattr(result, "title", ""))
    if titled and title:
        ax.set_title(title)
    _finish(ax, loc="best")

    def place() -> None:
        place_labels(ax, labels, clear_of=place_labels(ax, tags, within="figure"))
    return place


def _orbits_diagram(result: Any, ax: Any) -> Callable[[], None]:
    """The study's branches of periodic orbits on `ax` (study's diagram); returns what places
    their labels."""
    y: YAxis = "frequency" if getattr(result, "axis", "phase") == "frequency" else "phase:th2"
    drawn = _drawn(result.branches)
    label = ""
    if y == "phase:th2" and not any("th2" in getattr(b, "state_names", []) for b in drawn.values()):
        y, label = _widest_maximum(drawn)  # no pendula (an equation case file)
    seen: set = set()
    labels: list = []
    names: list = []  # the branches' names, placed first
    for name, b in drawn.items():
        events, tag = _draw_branch(ax, b, y, name, seen)
        labels += events
        names.append(tag)
    # The marked parameter sets (the paper's Fig. 9: the stiffness before and after the fit):
    # vertical dash-dotted lines, each named beside its line inside the axes (above them, the
    # names ran into the title), where its name crosses no curve, before the events' labels; on
    # two lines (on one, Fig. 9's table2 did not fit between its line and table3's).
    marks = []
    for m in getattr(result, "marks", None) or []:
        name, value = _field(m, "name"), float(_field(m, "value"))
        ax.axvline(value, color="0.3", lw=0.8, ls="-.", gid=f"mark {name}")
        marks.append(ax.annotate(f"{name}\n{math_name(result.parameter)} = {value:.4g}",
                                 (value, 1.0), xycoords=("data", "axes fraction"),
                                 textcoords="offset points", xytext=(2, -17), fontsize=6.5,
                                 color="0.3", gid="mark label"))
    ax.set_xlabel(axis_label(result.parameter))
    if y == "frequency":
        ax.set_ylabel("frequency (Hz)")
    elif callable(y):
        ax.set_ylabel(label)
    else:
        ax.set_ylabel(r"$|\theta_2 - \theta_1|$ (rad)")
        ax.set_yticks([0, math.pi / 2, math.pi], ["0", r"$\pi/2$", r"$\pi$"])
        ax.set_ylim(-0.4, math.pi + 0.4)
    if getattr(result, "title", ""):
        import textwrap
        # Wrapped to the axes' width (8-point text: about 4.5 points a character), 50
        # characters on a column's.
        width = ax.get_position().width * ax.figure.get_figwidth() * 72.0 / 4.5
        ax.set_title(textwrap.fill(result.title, max(40, int(width))))
    # The legend below the axes, in rows: inside, it took the room the events' labels need.
    _finish(ax, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=5, frameon=False,
            handlelength=1.8, columnspacing=1.0)

    def place() -> None:
        first = place_labels(ax, names, within="figure")
        first += place_labels(ax, marks, clear_of=first, reach=None)  # anywhere along its line
        place_labels(ax, labels, clear_of=first)
    return place


def _widest_maximum(branches: dict) -> tuple[YAxis, str]:
    """For branches without pendula: the maximum over the orbit of the state whose maximum
    varies most along them (the pitchfork of cycles' w = +-sqrt(mu), where x's is 1 throughout),
    and its label."""
    first = next(iter(branches.values()), None)
    if first is None or not hasattr(first.points, "max"):
        return None, ""
    names = list(first.state_names)
    spread = {n: np.ptp(np.concatenate([_by_name(b.points.max, names)[n] for b in branches.values()]))
              for n in names}
    state = max(names, key=lambda n: spread[n])
    return (lambda p: _by_name(p.max, names)[state]), f"max of {math_name(state)}"


def _study_diagram(result: Any, ax: Any) -> None:
    """For basins(), whose argument `study` hides study's name: the orbits' diagram on `ax`."""
    _orbits_diagram(result, ax)()


def curve(result: Any, ax: Any = None) -> Any:
    """A two-parameter curve (a fold, branch point, period doubling or Neimark-Sacker curve) in
    its two parameters, its codimension-two points marked. Returns the axes."""
    ax = new_axes(ax)
    p = result.points
    first, second = np.asarray(p.first, dtype=float), np.asarray(p.second, dtype=float)
    ax.plot(first, second, color="black", lw=1.4, gid="curve", label=f"{result.kind} curve")
    labels = _events(ax, list(result.events), lambda e: (float(e.first), float(e.second)),
                     lambda e: float(e.first))
    # The engine's result names its parameters first_name and second_name; the program's JSON,
    # read back by sympathy.load, first and second.
    first_name = _field(result, "first_name") or _field(result, "first")
    second_name = _field(result, "second_name") or _field(result, "second")
    ax.set_xlabel(axis_label(str(first_name)))
    ax.set_ylabel(axis_label(str(second_name)))
    _finish(ax, loc="best")
    place_labels(ax, labels)
    return ax


def oscillation_phase(t: Any, x: Any) -> np.ndarray:
    """The phase (rad, unwrapped) of an oscillating signal at the times `t`: 2 pi k at its k-th
    upward zero crossing (linear between samples), linear in time between crossings; NaN before
    the first and after the last."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    up = np.nonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))[0]
    crossings = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    if len(crossings) < 2:
        return np.full(len(t), np.nan)
    phase = np.interp(t, crossings, 2.0 * np.pi * np.arange(len(crossings)))
    phase[(t < crossings[0]) | (t > crossings[-1])] = np.nan
    return phase


def phase_differences(result: Any) -> dict[str, np.ndarray]:
    """Each angle's phase minus the first angle's (th2 - th1, ...), wrapped to [-pi/2, 3 pi/2),
    over a simulation's times: 0 in phase, pi in anti-phase (no jump where it wanders about pi;
    the paper's Figs. 3 and 5)."""
    names = list(result.state_names)
    angles = [n for n in names if n.startswith("th") and n[2:].isdigit()]
    if len(angles) < 2:
        return {}
    states = np.asarray(result.states)
    phases = {n: oscillation_phase(result.t, states[:, names.index(n)]) for n in angles}
    reference = phases[angles[0]]
    out = {}
    for n in angles[1:]:
        d = phases[n] - reference
        out[n] = np.mod(d + 0.5 * np.pi, 2.0 * np.pi) - 0.5 * np.pi
    return out


def simulation(result: Any, ax: Any = None, states: Optional[list[str]] = None,
               phases: Optional[bool] = None) -> Any:
    """A simulation's states against time (`states`: by name, by default every one); with
    `phases` (by default where there are two angles or more and no `ax` is given) a second panel
    below of each angle's phase difference to the first, where a slide from anti-phase to in-phase
    shows even when the angles' band does not. Returns the top axes."""
    names = list(result.state_names)
    differences = phase_differences(result) if phases is not False and ax is None else {}
    if ax is None and differences:
        import matplotlib.pyplot as plt  # type: ignore[import]
        fig, (ax, below) = plt.subplots(2, 1, figsize=(COLUMN[0], 1.5 * COLUMN[1]), sharex=True,
                                        layout="constrained", height_ratios=[3, 2])
        for n, d in differences.items():
            below.plot(result.t, d, lw=0.8, label=f"{math_name(n)} $-$ {math_name('th1')}",
                       gid=f"phase {n}")
        below.set_ylabel("phase difference")
        below.set_yticks([0, np.pi], ["0", r"$\pi$"])
        below.set_ylim(-0.5 * np.pi, 1.5 * np.pi)
        below.set_xlabel("t (s)")
        _finish(below, loc="best")
    ax = new_axes(ax)
    for name in states or names:
        ax.plot(result.t, np.asarray(result.states)[:, names.index(name)], lw=0.8,
                label=math_name(name))
    if not differences:
        ax.set_xlabel("t (s)")
    _finish(ax, loc="best", ncol=2)
    return ax



def time_series(result: Any, t_from: float = 0.0, title: str = "") -> Any:
    """A metronome case's simulation in the layout of the paper's Figs. 3 and 5, with the phase
    difference between them: the pendulum angles on top, each angle's phase difference to th1
    below them (where the slide from anti-phase to in-phase shows), the platform's displacement
    (mm) at the bottom; from `t_from` on. Returns the top axes."""
    import matplotlib.pyplot as plt  # type: ignore[import]
    names = list(result.state_names)
    states = np.asarray(result.states)
    t = np.asarray(result.t, dtype=float)
    angles = [n for n in names if n.startswith("th") and n[2:].isdigit()]
    platform = [n for n in names if n in ("x", "y")]
    differences = phase_differences(result)
    rows = [r for r in ("angles", "phases", "platform")
            if (r == "angles" and angles) or (r == "phases" and differences)
            or (r == "platform" and platform)]
    if not rows:
        return simulation(result)
    heights = {"angles": 3, "phases": 2, "platform": 2}
    fig, axes = plt.subplots(len(rows), 1, figsize=(7.0, 0.9 * sum(heights[r] for r in rows)),
                             sharex=True, layout="constrained",
                             height_ratios=[heights[r] for r in rows], squeeze=False)
    keep = t >= t_from
    for ax, row in zip(axes[:, 0], rows):
        if row == "angles":
            for n in angles:
                ax.plot(t[keep], states[keep, names.index(n)], lw=0.6, label=math_name(n))
            ax.set_ylabel("angle (rad)")
            _finish(ax, loc="upper right", ncol=len(angles))
        elif row == "phases":
            for n, d in differences.items():
                ax.plot(t[keep], d[keep], lw=0.9, label=f"{math_name(n)} $-$ {math_name('th1')}",
                        gid=f"phase {n}")
            ax.set_yticks([0, np.pi], ["0", r"$\pi$"])
            ax.set_ylim(-0.5 * np.pi, 1.5 * np.pi)
            ax.set_ylabel("phase difference")
            _finish(ax, loc="upper right", ncol=len(differences))
        else:
            for n in platform:
                ax.plot(t[keep], 1e3 * states[keep, names.index(n)], lw=0.6,
                        label=math_name(n))
            ax.set_ylabel("platform (mm)")
            _finish(ax, legend=len(platform) > 1, loc="upper right")
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel("t (s)")
    axes[-1, 0].xaxis.label.set_fontsize(8)
    if title:
        axes[0, 0].set_title(title, fontsize=8)
    return axes[0, 0]


def _field(obj: Any, key: str, default: Any = None) -> Any:
    """A field of a result read back from JSON (a dict) or returned by a function (attributes)."""
    if isinstance(obj, dict):
        return obj.get(key, default)
    return getattr(obj, key, default)


CURVE_COLORS = {"BP": "tab:blue", "NS": "tab:purple", "LP": "black", "PD": "tab:orange"}
# The equilibria's fold and Hopf curves on a map, dashed beside the cycles' solid curves.
EQUILIBRIUM_CURVE_COLORS = {"LP": "0.3", "HB": "tab:green"}
STABLE_SHADE, UNSTABLE_SHADE = "#c8e6c9", "#f4c7c3"


# The codes of stability_regions: what a point of the map's plane is for one orbit.
REGION_UNSTABLE, REGION_STABLE, REGION_NO_ORBIT, REGION_NOT_SAMPLED = 0, 1, 2, 3
REGION_SHADES = [UNSTABLE_SHADE, STABLE_SHADE, "white", "#fff59d"]  # not sampled: pale yellow


def _shifted(values: np.ndarray) -> list[np.ndarray]:
    """The values of each point's four neighbours (-1 beyond the edges)."""
    out = []
    for axis in (0, 1):
        for step in (1, -1):
            s = np.full_like(values, -1)
            if axis == 0:
                s[max(step, 0):values.shape[0] + min(step, 0)] = \
                    values[max(-step, 0):values.shape[0] + min(-step, 0)]
            else:
                s[:, max(step, 0):values.shape[1] + min(step, 0)] = \
                    values[:, max(-step, 0):values.shape[1] + min(-step, 0)]
            out.append(s)
    return out


def _spread(codes: np.ndarray, into: np.ndarray) -> np.ndarray:
    """Each unassigned (-1) point of `into` takes a neighbour's code, step after step (a
    breadth-first spread from the assigned points, so each takes the code of the one nearest
    along paths inside `into`), until nothing changes."""
    codes = codes.copy()
    while True:
        todo = (codes < 0) & into
        if not todo.any():
            return codes
        changed = False
        for neighbour in _shifted(codes):
            take = todo & (codes < 0) & (neighbour >= 0)
            if take.any():
                codes[take] = neighbour[take]
                changed = True
        if not changed:
            return codes


def _walls(orbit: Any, window: tuple, shape: tuple[int, int]) -> np.ndarray:
    """The raster's points that an event curve of the orbit passes through (its neutral-saddle
    parts left out: crossing one changes no stability), as an 8-connected chain, which no
    4-connected path crosses."""
    (x0, x1), (y0, y1) = window
    rows, cols = shape
    walls = np.zeros(shape, dtype=bool)
    for curve in _field(orbit, "curves", []):
        points = curve.points
        u = (np.asarray(points.first, dtype=float) - x0) / (x1 - x0) * cols
        v = (np.asarray(points.second, dtype=float) - y0) / (y1 - y0) * rows
        saddle = np.asarray(getattr(points, "neutral_saddle", np.zeros(len(u))), dtype=bool)
        for i in range(len(u) - 1):
            if saddle[i]:  # the segment drawn dotted (_map_curves)
                continue
            n = int(math.ceil(2.0 * max(abs(u[i + 1] - u[i]), abs(v[i + 1] - v[i])))) + 1
            f = np.linspace(0.0, 1.0, n + 1)
            su, sv = u[i] + f * (u[i + 1] - u[i]), v[i] + f * (v[i + 1] - v[i])
            inside = (su >= 0) & (su <= cols) & (sv >= 0) & (sv <= rows)
            c = np.minimum(su[inside].astype(int), cols - 1)
            r = np.minimum(sv[inside].astype(int), rows - 1)
            walls[r, c] = True
    return walls


def stability_regions(orbit: Any, shape: tuple[int, int] = (300, 400)) -> \
        Optional[tuple[np.ndarray, tuple]]:
    """An orbit of a map on a raster of its grid's window, finer than the grid (`shape`: rows
    along the second parameter, columns along the first), as the regions its computed curves
    bound: each raster point takes the state of the grid point nearest to it along paths that
    cross none of the orbit's event curves (REGION_UNSTABLE, REGION_STABLE, REGION_NO_ORBIT;
    REGION_NOT_SAMPLED in a region that holds no grid point, such as a sliver between two close
    curves). A region bounded by curves on all sides is thus one state, its edge the curves' own
    line, not the grid's cells; where the grid's points in one region disagree (a curve not
    computed, the orbit lost by the grid's own continuation), the border between them is midway,
    as the grid's cells would have it. Returns the codes (rows: second parameter, upwards) and
    the window ((first0, first1), (second0, second1)), or None without a grid."""
    grid = _field(orbit, "grid")
    if not grid:
        return None
    first = np.asarray(_field(grid, "first"), dtype=float)
    second = np.asarray(_field(grid, "second"), dtype=float)
    count = np.asarray(_field(grid, "unstable_count"), dtype=int)
    window = ((float(first[0]), float(first[-1])), (float(second[0]), float(second[-1])))
    if window[0][0] == window[0][1] or window[1][0] == window[1][1]:
        return None
    rows, cols = shape
    walls = _walls(orbit, window, shape)
    codes = np.full(shape, -1, dtype=int)
    c = np.minimum(((first - first[0]) / (first[-1] - first[0]) * cols).astype(int), cols - 1)
    r = np.minimum(((second - second[0]) / (second[-1] - second[0]) * rows).astype(int),
                   rows - 1)
    for i, row in enumerate(r):
        for j, col in enumerate(c):
            if not walls[row, col]:  # a grid point on a curve tells neither side
                n = count[i, j]
                codes[row, col] = (REGION_NO_ORBIT if n < 0 else REGION_STABLE if n == 0
                                   else REGION_UNSTABLE)
    codes = _spread(codes, ~walls)
    codes[(codes < 0) & ~walls] = REGION_NOT_SAMPLED
    # The curves' own points: a neighbour's state (the curve is drawn over them).
    codes = _spread(codes, walls)
    codes[codes < 0] = REGION_NOT_SAMPLED
    return codes, window


def _map_curves(ax: Any, orbit: Any, drawn: set, colors: Optional[dict] = None, of: str = "",
                style: str = "-") -> list:
    """The orbit's event curves (an NS curve dotted where it is a neutral saddle: its pair is
    real, no bifurcation), their codimension-two points marked; returns the points' labels.
    An equilibria entry's fold and Hopf curves likewise, in `colors` and `style`, their legend
    entries ending in `of` (a Hopf curve of equilibria dotted where it is a neutral saddle)."""
    colors = colors or CURVE_COLORS
    labels = []
    for curve in _field(orbit, "curves", []):
        points = curve.points
        first = np.asarray(points.first, dtype=float)
        second = np.asarray(points.second, dtype=float)
        if len(first) == 0:
            continue
        kind = curve.kind
        color = colors.get(kind, "0.4")
        saddle = np.asarray(getattr(points, "neutral_saddle", np.zeros(len(first))), dtype=bool)
        start = 0
        for i in range(1, len(first) + 1):
            if i < len(first) and saddle[i] == saddle[start]:
                continue
            name = f"{kind}{of}: neutral saddle" if saddle[start] else f"{kind} curve{of}"
            ax.plot(first[start:i + 1], second[start:i + 1], color=color, lw=1.3,
                    ls=":" if saddle[start] else style, gid=f"curve {kind}{of}",
                    label=None if name in drawn else name)
            drawn.add(name)
            start = i
        for e in curve.events:
            if str(e.type).startswith("turn") or str(e.type) == "UZ":
                continue
            # A point two curves meet at (a BT on the fold and on the Hopf curve) marked once.
            point = (str(e.type), round(float(e.first), 6), round(float(e.second), 6))
            if point in drawn:
                continue
            drawn.add(point)
            ax.plot([e.first], [e.second], marker="o", ms=3.5, color=color, mfc="white",
                    ls="none", zorder=5, gid=f"event {e.type}")
            labels.append(ax.annotate(str(e.type), (e.first, e.second),
                                      textcoords="offset points", xytext=(3, 3), fontsize=6.5,
                                      color=color, gid="event label"))
    return labels


def _marks(ax: Any, marks: list, window: Optional[tuple] = None) -> list:
    """The case's parameter sets starred; hollow, with what differs, off the map's plane; those
    outside the map's `window` ((x0, x1), (y0, y1)) left out."""
    labels = []
    for m in marks or []:
        inside = _field(m, "in_plane", True)
        x, y = _field(m, "first"), _field(m, "second")
        if window and not (min(window[0]) <= x <= max(window[0]) and
                           min(window[1]) <= y <= max(window[1])):
            continue
        ax.plot([x], [y], marker="*", ms=7, color="black", mfc="black" if inside else "white",
                ls="none", zorder=6, gid="event mark")
        # Off the plane: what differs on a second line (one line was wider than a map's panel).
        text = _field(m, "name") if inside else f"{_field(m, 'name')}\n({_field(m, 'off_plane')})"
        labels.append(ax.annotate(text, (x, y), textcoords="offset points", xytext=(6, 3),
                                  fontsize=6.5, gid="event label"))
    return labels


def _shade(ax: Any, codes: np.ndarray, window: tuple, colors: list) -> None:
    """Codes 0, 1, ... on the map's window in `colors` (an image, each raster point a block)."""
    from matplotlib.colors import ListedColormap  # type: ignore[import]
    ax.imshow(codes, origin="lower", extent=(*window[0], *window[1]), aspect="auto",
              interpolation="nearest", cmap=ListedColormap(colors), vmin=-0.5,
              vmax=len(colors) - 0.5, gid="shading", zorder=0)


def _equilibria_curves(ax: Any, result: Any, drawn: set) -> list:
    """Every equilibria entry's fold and Hopf curves (dashed), their codimension-two points
    marked; returns the points' labels."""
    labels = []
    for entry in _field(result, "equilibria", None) or []:
        labels += _map_curves(ax, entry, drawn, EQUILIBRIUM_CURVE_COLORS, " of equilibria", "--")
    return labels


def _map_window(result: Any) -> Optional[tuple]:
    """The map's window ((first from, to), (second from, to)): the JSON's axes, or the window
    sympathy.map returns."""
    first, second = _field(result, "first"), _field(result, "second")
    if isinstance(first, str) or first is None:
        return _field(result, "window")
    return ((_field(first, "from"), _field(first, "to")),
            (_field(second, "from"), _field(second, "to")))


def stability_map(result: Any, ax: Any = None) -> Any:
    """A stability map (``sympathy map``): per orbit a panel, shaded where it is stable, unstable
    or not found, by the regions its computed curves bound (stability_regions: the shading's
    edges are the curves, not the grid's cells), with those curves (a legend entry per curve
    kind) and their codimension-two points, the case's parameter sets starred; with two or more
    orbits, a last panel of where only one of the first two, both or neither is stable. The
    equilibria entries' fold and Hopf curves dashed on every panel (a map of equilibria alone:
    one panel of them). Returns the first panel's axes."""
    import matplotlib.pyplot as plt  # type: ignore[import]
    from matplotlib.patches import Patch  # type: ignore[import]

    orbits = list(result.orbits)
    first, second = _field(result, "first"), _field(result, "second")
    first_name = first if isinstance(first, str) else _field(first, "parameter")
    second_name = second if isinstance(second, str) else _field(second, "parameter")
    if not orbits:  # equilibria only: one panel of their curves
        ax = new_axes(ax)
        labels = _marks(ax, _field(result, "marks", []), _map_window(result)) + \
            _equilibria_curves(ax, result, set())
        window = _map_window(result)
        if window:
            ax.set_xlim(*window[0])
            ax.set_ylim(*window[1])
        ax.set_title("equilibria")
        ax.set_xlabel(axis_label(first_name))
        ax.set_ylabel(axis_label(second_name))
        _finish(ax, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=2, frameon=False)
        if _field(result, "title"):
            import textwrap
            ax.figure.suptitle(textwrap.fill(_field(result, "title"), 90), fontsize=8)
        place_labels(ax, labels)
        return ax
    panels = len(orbits) + (1 if len(orbits) > 1 else 0)
    if ax is None:
        fig, axes = plt.subplots(1, panels, figsize=(min(7.0, 3.4 * panels), 2.8), sharey=True,
                                 squeeze=False, layout="constrained")
        axes = list(axes[0])
    else:
        axes = [ax]
        orbits = orbits[:1]
    regions = []
    to_place: list = []  # (panel, its labels), placed once every panel is drawn
    for panel, orbit in zip(axes, orbits):
        region = stability_regions(orbit)
        regions.append(region)
        window = region[1] if region else None
        handles = []
        if region is not None:
            codes, window = region
            _shade(panel, codes, window, REGION_SHADES)
            handles = [Patch(color=STABLE_SHADE, label="stable"),
                       Patch(color=UNSTABLE_SHADE, label="unstable"),
                       Patch(facecolor="white", edgecolor="0.7", label="no orbit")]
            if (codes == REGION_NOT_SAMPLED).any():
                handles.append(Patch(color=REGION_SHADES[REGION_NOT_SAMPLED], label="not sampled"))
        drawn: set = set()
        # The parameter sets' labels placed first: fewer and longer than the curves' points'.
        labels = _marks(panel, _field(result, "marks", []), window) + \
            _map_curves(panel, orbit, drawn) + _equilibria_curves(panel, result, drawn)
        if window:  # the map's window: the grid's first and last values
            panel.set_xlim(*window[0])
            panel.set_ylim(*window[1])
        panel.set_title(_field(orbit, "name"))
        panel.set_xlabel(axis_label(first_name))
        handles += [h for h in panel.get_legend_handles_labels()[0]]
        # Below the panel: inside it would cover the curves.
        _finish(panel, handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.3), ncol=2,
                frameon=False)
        to_place.append((panel, labels))
    if len(axes) > len(orbits) and all(r is not None for r in regions[:2]) and \
            regions[0][1] == regions[1][1]:  # type: ignore[index]
        panel = axes[-1]
        (a, window), (b, _) = regions[0], regions[1]  # type: ignore[misc]
        # Where an orbit is not found it is not stable; unsampled where either is.
        both = (a == REGION_STABLE) + 2 * (b == REGION_STABLE)
        both[(a == REGION_NOT_SAMPLED) | (b == REGION_NOT_SAMPLED)] = 4
        colors = ["#e0e0e0", "#bbdefb", "#ffe0b2", STABLE_SHADE, REGION_SHADES[REGION_NOT_SAMPLED]]
        _shade(panel, both, window, colors)
        drawn = set()
        labels = []
        for orbit in orbits[:2]:
            labels += _map_curves(panel, orbit, drawn)
        labels += _equilibria_curves(panel, result, drawn)
        panel.set_xlim(*window[0])
        panel.set_ylim(*window[1])
        names = [_field(o, "name") for o in orbits[:2]]
        panel.set_title("stable: " + " / ".join(names))
        panel.set_xlabel(axis_label(first_name))
        handles = [Patch(color=colors[3], label="both"),
                   Patch(color=colors[1], label=f"only {names[0]}"),
                   Patch(color=colors[2], label=f"only {names[1]}"),
                   Patch(color=colors[0], label="neither")]
        if (both == 4).any():
            handles.append(Patch(color=colors[4], label="not sampled"))
        _finish(panel, handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.3), ncol=2,
                frameon=False)
        to_place.append((panel, labels))
    axes[0].set_ylabel(axis_label(second_name))
    axes[0].yaxis.label.set_fontsize(8)
    if _field(result, "title"):
        import textwrap
        axes[0].figure.suptitle(textwrap.fill(_field(result, "title"), 90), fontsize=8)
    for panel, labels in to_place:
        place_labels(panel, labels)
    return axes[0]


STATE_COLORS = {"in-phase": "tab:blue", "anti-phase": "tab:red", "in-in": "tab:blue",
                "anti-anti": "tab:red", "in-anti": "tab:purple",
                "not-synchronized": "tab:orange", "stopped": "0.3", "undetermined": "0.6",
                "failed": "black"}
# A marker per state as well as a colour: two states with the same shares (the mirror-image
# locked orbits born at a branch point, locked+2.95 and locked-2.95) were one line under another.
STATE_MARKERS = {"in-phase": "o", "anti-phase": "s", "in-in": "o", "anti-anti": "s",
                 "in-anti": "D", "not-synchronized": "D", "stopped": "X", "undetermined": "P",
                 "failed": "x"}
_OTHER_COLORS = ["tab:green", "tab:brown", "tab:pink", "tab:olive", "tab:cyan", "tab:gray"]
_OTHER_MARKERS = ["^", "v", "<", ">", "p", "h"]


def _basin_states(result: Any) -> list[str]:
    """The states of a basins result that won at least one run somewhere, in the order met."""
    states: list[str] = []
    for p in result.points:
        for state, share in _field(p, "shares").items():
            if _field(share, "count", 0) > 0 and state not in states:
                states.append(state)
    return states


def _state_styles(states: list[str]) -> dict[str, tuple[Any, str]]:
    """(colour, marker) by state: the named states' own, the others (locked states) the rest in
    turn."""
    styles = {}
    others = [s for s in states if s not in STATE_COLORS]
    for state in states:
        if state in STATE_COLORS:
            styles[state] = (STATE_COLORS[state], STATE_MARKERS.get(state, "o"))
        else:
            n = others.index(state)
            styles[state] = (_OTHER_COLORS[n % len(_OTHER_COLORS)],
                             _OTHER_MARKERS[n % len(_OTHER_MARKERS)])
    return styles


def _basins_title(result: Any) -> str:
    import os
    import textwrap
    details = (f"{os.path.basename(str(_field(result, 'case', '')))} "
               f"({_field(result, 'params', '')}): {_field(result, 'starts')} random starts a "
               f"point, angles in [{_field(result, 'angles')[0]:g}, "
               f"{_field(result, 'angles')[1]:g}] rad, {_field(result, 't_end'):g} s")
    title = _field(result, "title", "")
    return (textwrap.fill(title, 100) + "\n" if title else "") + details


def _basin_offsets(shares: np.ndarray, step: float) -> np.ndarray:
    """Horizontal offsets of the states' markers (rows: states in order, columns: grid points;
    NaN where a state won no run): where two or more states' shares at a grid point lie within
    0.04 of each other (their markers would cover one another), they are spread side by side,
    0.12 of the grid's step apart; every other marker stays on its grid value."""
    offsets = np.zeros(shares.shape)
    spacing = min(0.12, 0.8 / max(shares.shape[0], 1)) * step
    for i in range(shares.shape[1]):
        won = [n for n in range(shares.shape[0]) if not np.isnan(shares[n, i])]
        won.sort(key=lambda n: shares[n, i])
        clusters: list[list[int]] = []
        for n in won:
            if clusters and shares[n, i] - shares[clusters[-1][-1], i] < 0.04:
                clusters[-1].append(n)
            else:
                clusters.append([n])
        for cluster in clusters:
            for j, n in enumerate(sorted(cluster)):
                offsets[n, i] = (j - (len(cluster) - 1) / 2) * spacing
    return offsets


def _basin_shares(ax: Any, result: Any) -> None:
    """The shares over a one-parameter grid on `ax`: per state its markers where it won runs,
    with their 95% intervals, and a line through them down to 0 at the neighbouring grid points
    (a state that won at neither end of a step has no line there: the zero shares' lines and
    intervals were a clutter along the bottom); each state its colour and marker, and markers
    that would cover one another side by side; the legend beside the axes."""
    from matplotlib.lines import Line2D  # type: ignore[import]
    parameter = _field(_field(result, "grid")[0], "parameter")
    points = [p for p in result.points if _field(p, "runs", 0)]
    states = _basin_states(result)
    styles = _state_styles(states)
    xs = np.array([_field(p, "values")[parameter] for p in points], dtype=float)
    unique = np.unique(xs)
    step = float(np.min(np.diff(unique))) if len(unique) > 1 else 1.0
    table = [[_field(p, "shares").get(state) for p in points] for state in states]
    won = np.array([[q is not None and _field(q, "count", 0) > 0 for q in row] for row in table],
                   dtype=bool).reshape(len(states), len(points))
    y = np.array([[_field(q, "share", 0.0) if q is not None else 0.0 for q in row]
                  for row in table]).reshape(len(states), len(points))
    offsets = _basin_offsets(np.where(won, y, np.nan), step)
    handles = []
    for n, state in enumerate(states):
        color, marker = styles[state]
        x = xs + offsets[n]
        near = won[n].copy()
        near[1:] |= won[n, :-1]
        near[:-1] |= won[n, 1:]
        ax.plot(x, np.where(near, y[n], np.nan), color=color, lw=1.0, gid=f"line {state}")
        at = np.flatnonzero(won[n])
        ax.plot(x[at], y[n, at], ls="none", marker=marker, ms=4, color=color, gid=state,
                zorder=3)
        lower = np.array([y[n, i] - _field(table[n][i], "lower") for i in at])
        upper = np.array([_field(table[n][i], "upper") - y[n, i] for i in at])
        ax.errorbar(x[at], y[n, at], yerr=[lower, upper], fmt="none", color=color, capsize=2,
                    lw=0.8, gid=f"interval {state}")
        handles.append(Line2D([], [], color=color, marker=marker, ms=4, lw=1.0, label=state))
    ax.set_xlim(unique[0] - 0.5 * step, unique[-1] + 0.5 * step)
    ax.set_ylim(-0.05, 1.05)
    ax.set_xlabel(axis_label(parameter))
    ax.set_ylabel("share of runs (95% interval)")
    ax.grid(alpha=0.25)
    # The legend beside the axes (inside, it covered the shares), at the axes' text size.
    _finish(ax, legend=False)
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False,
              fontsize=8)


def _basin_maps(fig: Any, result: Any) -> list:
    """A two-parameter grid: a map of the share per state that won anywhere, one colour bar."""
    grid = _field(result, "grid")
    p1, p2 = _field(grid[0], "parameter"), _field(grid[1], "parameter")
    states = _basin_states(result)
    axes = list(fig.subplots(1, len(states), squeeze=False, sharey=True)[0])
    xs = sorted({_field(p, "values")[p1] for p in result.points})
    ys = sorted({_field(p, "values")[p2] for p in result.points})

    def edges(values: list) -> list:  # cells centred on the values, half a step beyond each end
        half = 0.5 * (values[1] - values[0]) if len(values) > 1 else 0.5
        return [values[0] - half, values[-1] + half]

    image = None
    for ax, state in zip(axes, states):
        shares = np.full((len(ys), len(xs)), np.nan)
        for p in result.points:
            if _field(p, "runs", 0):
                share = _field(p, "shares").get(state)
                shares[ys.index(_field(p, "values")[p2]), xs.index(_field(p, "values")[p1])] = \
                    _field(share, "share", 0.0) if share is not None else 0.0
        image = ax.imshow(shares, origin="lower", aspect="auto", vmin=0, vmax=1, cmap="viridis",
                          extent=(*edges(xs), *edges(ys)), gid=f"share {state}")
        ax.set_title(state)
        ax.set_xlabel(axis_label(p1))
        _finish(ax, legend=False)
    axes[0].set_ylabel(axis_label(p2))
    axes[0].yaxis.label.set_fontsize(8)
    bar = fig.colorbar(image, ax=axes, label="share of runs")
    bar.ax.tick_params(labelsize=8)
    bar.ax.yaxis.label.set_fontsize(8)
    return axes


def _basin_runs(result: Any, point: int) -> list[dict]:
    """The runs of a basins result at one grid point, from its runs CSV (``runs_csv``, beside
    the JSON the result was read from): dicts of the CSV's columns (th1_0, th2_0, class, ...)."""
    import csv
    import os
    points = list(result.points)
    if not 0 <= point < len(points):
        raise ValueError(f"point {point}: expected a grid point 0 .. {len(points) - 1}")
    path = os.path.join(os.path.dirname(str(_field(result, "path", ""))),
                        str(_field(result, "runs_csv", "")))
    try:
        with open(path, newline="") as f:
            rows = [r for r in csv.DictReader(f) if int(r["point"]) == point]
    except OSError as e:
        raise ValueError(f"{path}: the runs cannot be read ({e.strerror})") from None
    if not rows:
        raise ValueError(f"{path}: no runs at grid point {point}")
    return rows


def _basin_starts(ax: Any, result: Any, point: int) -> None:
    """The basin at one grid point: each run's start angles (th1, th2) in its final state's
    colour and marker."""
    rows = _basin_runs(result, point)
    # The states in the order, colours and markers of the shares' figure.
    everywhere = _basin_states(result)
    here = set(r["class"] for r in rows)
    states = [s for s in everywhere if s in here] + sorted(here - set(everywhere))
    styles = _state_styles(everywhere + [s for s in states if s not in everywhere])
    for state in states:
        chosen = [r for r in rows if r["class"] == state]
        color, marker = styles[state]
        ax.plot([float(r["th1_0"]) for r in chosen], [float(r["th2_0"]) for r in chosen],
                ls="none", marker=marker, ms=4, color=color, gid=state,
                label=f"{state} ({len(chosen)})")
    values = ", ".join(f"{math_name(k)} = {v:g}"
                       for k, v in _field(list(result.points)[point], "values").items())
    initial = ", ".join(f"{math_name(k)} = {v:g}"
                        for k, v in (_field(result, "initial") or {}).items())
    ax.set_title(f"basin at {values}: start angles, " + (initial or "platform at rest"))
    ax.set_xlabel(r"$\theta_1$ at t = 0 (rad)")
    ax.set_ylabel(r"$\theta_2$ at t = 0 (rad)")
    ax.set_aspect("equal")
    ax.grid(alpha=0.25)
    _finish(ax, loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False)


def basins(result: Any, ax: Any = None, study: Any = None, point: Optional[int] = None) -> Any:
    """Basins of attraction (``sympathy basins``; its result, or its JSON read by
    ``sympathy.load``). Over one parameter: each state's share of the runs at each grid point
    with its 95% Wilson interval, every state that won a run somewhere in its colour and
    marker, a marker and an interval only where it won (none at a zero share), a line through
    them down to 0 at the neighbouring points, markers that would cover one another side by
    side; with `study` (a study of the same parameter, as ``sympathy.study`` returns it or
    ``sympathy.load`` reads its JSON) its stability diagram below, on the same axis. Over two
    parameters: a map of the share per state. With `point` (a grid point's index): the basin
    there, each run's start angles in its final state's colour and marker (from the runs CSV
    beside the JSON). On a new figure a page wide (7 inches), the study's title and how the
    runs were made above; `ax` only for the shares or a point's basin. Returns the (first)
    axes."""
    import matplotlib.pyplot as plt  # type: ignore[import]
    grid = list(_field(result, "grid"))
    new = ax is None
    if point is not None:
        if new:
            fig, ax = plt.subplots(figsize=(5.0, 3.6), layout="constrained")
        _basin_starts(ax, result, point)
    elif len(grid) == 2:
        if not new:
            raise ValueError("plot: basins over two parameters draw a panel per state; no ax")
        fig = plt.figure(figsize=(7.0, 2.9), layout="constrained")
        ax = _basin_maps(fig, result)[0]
    elif len(grid) != 1:
        raise ValueError(f"plot: expected basins over one or two parameters, not {len(grid)}")
    elif study is not None:
        if not new:
            raise ValueError("plot: basins with a study draw two panels; no ax")
        parameter = _field(grid[0], "parameter")
        if _field(study, "parameter") != parameter:
            raise ValueError(f"plot: the study's parameter is {_field(study, 'parameter')}; "
                             f"expected {parameter}, the basins grid's")
        fig, (ax, below) = plt.subplots(2, 1, figsize=(7.0, 5.4), sharex=True,
                                        layout="constrained", height_ratios=[1.0, 1.15])
        _basin_shares(ax, result)
        ax.set_xlabel("")
        fig.suptitle(_basins_title(result), fontsize=8)
        # The study drawn last: its labels are placed once the layout is done (place_labels).
        _study_diagram(study, below)
        return ax
    else:
        if new:
            fig, ax = plt.subplots(figsize=(7.0, 2.8), layout="constrained")
        _basin_shares(ax, result)
    if new:
        ax.figure.suptitle(_basins_title(result), fontsize=8)
    return ax


def _state_unit(name: str) -> str:
    """A metronome state's unit: m for x and y, rad for an angle, per second for a velocity."""
    position = name[1:] if name.startswith("v") and len(name) > 1 else name
    base = "m" if position in ("x", "y") else "rad"
    return base + "/s" if position != name else base


def fitted_unit(name: str) -> str:
    """The unit of a fitted unknown: a metronome parameter's ("d": N m s) or an initial state's
    ("th1(0)": rad); "" where unknown (an equation case file's names)."""
    if name.endswith("(0)"):
        state = name[:-3]
        return _state_unit(state) if state.lstrip("v")[:2] in ("th", "x", "y") else ""
    return UNITS.get(name.rstrip("0123456789"), "")


def fit(t: Any, data: dict, model: dict, unknowns: Optional[list] = None,
        title: Optional[str] = None) -> Any:
    """A recording against the model fitted to it (``sympathy fit``): per recorded state the data
    (dots) and the fitted model (a line) on top, the residuals (data - model) below with their
    RMS; platform positions in mm, angles in rad. `data` and `model`: arrays by state name at the
    times `t`; `unknowns`: the fit JSON's (name, value, error), written in the title with their
    units and standard errors unless `title` is given. Returns the first panel's axes."""
    import matplotlib.pyplot as plt  # type: ignore[import]
    t = np.asarray(t, dtype=float)
    names = [n for n in data if n != "t" and n in model]
    fig, axes = plt.subplots(2 * len(names), 1, figsize=(7.0, 0.6 + 2.0 * len(names)),
                             sharex=True, squeeze=False, layout="constrained",
                             height_ratios=[3, 1.2] * len(names))
    for k, name in enumerate(names):
        unit = _state_unit(name)
        factor, unit = (1e3, unit.replace("m", "mm", 1)) if unit.startswith("m") else (1.0, unit)
        top, bottom = axes[2 * k][0], axes[2 * k + 1][0]
        d = factor * np.asarray(data[name], dtype=float)
        m = factor * np.asarray(model[name], dtype=float)
        top.plot(t, d, ".", ms=1.5, color="0.55", label="data", gid=f"data {name}")
        top.plot(t, m, "-", lw=0.8, color="C0", label="fitted model", gid=f"model {name}")
        top.set_ylabel(f"{math_name(name)} ({unit})")
        # The legend above the panel's right corner: inside, it covered the largest swings.
        _finish(top, loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=2, frameon=False,
                borderaxespad=0.0)
        residual = d - m
        rms = float(np.sqrt(np.mean(residual ** 2))) if len(residual) else 0.0
        bottom.plot(t, residual, ".", ms=1.2, color="C3", gid=f"residual {name}")
        bottom.axhline(0.0, color="k", lw=0.5)
        bottom.set_ylabel("residual")
        bottom.text(0.01, 0.95, f"RMS {rms:.3g} {unit}", transform=bottom.transAxes, va="top",
                    fontsize=7, bbox=dict(facecolor="white", edgecolor="none", pad=1.0))
        _finish(bottom, legend=False)
    axes[-1][0].set_xlabel("t (s)")
    axes[-1][0].xaxis.label.set_fontsize(8)
    if title is None and unknowns:
        parts = []
        for u in unknowns:
            error = _field(u, "error")
            spread = f" $\\pm$ {error:.2g}" if error is not None and math.isfinite(error) \
                else " (undetermined)"
            unit = f" {fitted_unit(_field(u, 'name'))}" if fitted_unit(_field(u, "name")) else ""
            parts.append(f"{_field(u, 'name')} = {_field(u, 'value'):.5g}{spread}{unit}")
        title = "fitted: " + ",  ".join(parts)
    if title:
        fig.suptitle(title, fontsize=8)
    return axes[0][0]


def _number(text: Any) -> float:
    """A bench CSV's field as a number (NaN for '-', '' or text)."""
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def _tolerance(value: float) -> str:
    """A tolerance as a reader writes it: 1e-6, 5e-12."""
    import re
    return re.sub(r"e([-+])0*(\d)", r"e\1\2", f"{value:g}").replace("e+", "e")


BENCH_WIDTH = 7.0  # inches: a page's text width, two panels a row


def _two_decades(ax: Any) -> None:
    """Each logarithmic axis of `ax` made to show at least two powers of ten, its limits moved
    out to the nearer next one while it shows fewer, and no labels on the minor ticks (within
    one decade matplotlib labelled them, 2, 3, 4 and 6 x 10^-2 running into each other)."""
    from matplotlib.ticker import NullFormatter  # type: ignore[import]
    for get, set_, axis in ((ax.get_xlim, ax.set_xlim, ax.xaxis),
                            (ax.get_ylim, ax.set_ylim, ax.yaxis)):
        if axis.get_scale() != "log":
            continue
        lo, hi = (math.log10(v) for v in get())
        while math.floor(hi) - math.ceil(lo) < 1:
            up, down = math.floor(hi) + 1 - hi, lo - (math.ceil(lo) - 1)
            if up <= down:
                hi = math.floor(hi) + 1
            else:
                lo = math.ceil(lo) - 1
        set_(10.0 ** lo, 10.0 ** hi)
        axis.set_minor_formatter(NullFormatter())


def bench(rows: list[dict], scaling: Optional[list[dict]] = None,
          sections: Optional[str] = None) -> Any:
    """The accuracy report of ``sympathy bench`` (`rows`: its bench.csv as dicts by column;
    `scaling`: its scaling.csv's, for section (e)): per problem a panel of the error against the
    run time, one line per family of settings (a tolerance sweep, loose to tight), the accuracy
    presets as stars (hollow without the symmetry reduction), AUTO-07p's measured points as
    black crosses; section (e) the cost of one period with the monodromy against the number of
    metronomes, per linear solver. Section (f) on sympathy's CPU seconds where the bench wrote
    them. `sections`: only these letters' panels (e.g. "f"). A page wide (7 inches), two panels
    a row, every text 8 points: a panel whose legend is long (more than six entries) has its
    legend in the slot beside it; the other panels share one legend (a colour per family
    throughout), in a free slot or a row below them. Returns the first panel's axes."""
    import textwrap

    import matplotlib.pyplot as plt  # type: ignore[import]

    def letter(problem: str) -> str:
        return problem[1:2] if problem.startswith("(") else ""

    rows = [r for r in rows if not sections or letter(r["problem"]) in sections]
    costs: list[dict] = [r for r in scaling or [] if _number(r.get("seconds")) > 0] \
        if not sections or "e" in sections else []
    problems = list(dict.fromkeys(r["problem"] for r in rows))
    panels: list[tuple[str, str]] = [(letter(p), p) for p in problems]
    cost = "(e) cost against the number of metronomes"  # scaling.csv's panel
    if costs:
        panels.append(("e", cost))
    panels.sort(key=lambda panel: panel[0])
    if not panels:
        raise ValueError("plot: no bench rows to draw" + (f" in sections {sections}"
                                                          if sections else ""))

    # Each panel's series: (label, colour key, style, xs, ys).
    Series = tuple[str, str, dict, list, list]

    def series_of(problem: str) -> list[Series]:
        mine = [r for r in rows if r["problem"] == problem]
        in_k = letter(problem) in ("c", "f")
        key = "parameter_error" if in_k else "multiplier_error"
        out: list[Series] = []
        auto = [r for r in mine if r["converged"] == "AUTO-07p"]
        if auto:
            out.append(("AUTO-07p (AUTO's measurements)", "AUTO-07p",
                        dict(ls="none", marker="x", ms=6, mew=1.3, color="black", zorder=4),
                        [_number(r["seconds"]) for r in auto], [_number(r[key]) for r in auto]))
        for name in dict.fromkeys(r["setting"] for r in mine if r["converged"] != "AUTO-07p"):
            chosen = [r for r in mine if r["setting"] == name and r["converged"] == "yes"]
            # Section (f) on its CPU seconds where the bench wrote them (a shared machine's
            # wall time is not the run's); AUTO's points are its own whole-process times.
            clock = "cpu_seconds" if letter(problem) == "f" and chosen and all(
                _number(r.get("cpu_seconds")) > 0 for r in chosen) else "seconds"
            points = [(_number(r[clock]), _number(r[key]), _number(r["rtol"])) for r in chosen]
            points = [p for p in points if p[1] > 0]
            if not points:
                continue
            xs, ys, tolerances = (list(v) for v in zip(*points))
            if name.startswith("preset "):
                whole = name.endswith(", whole state")
                out.append((f"{name} (rtol {_tolerance(tolerances[0])})",
                            name.removesuffix(", whole state"),
                            dict(ls="none", marker="*", ms=10, mew=1.0, zorder=4,
                                 mfc="white" if whole else None), xs, ys))
            else:
                out.append((name, name, dict(ls="-", marker="o", ms=3, lw=1.2), xs, ys))
        return out

    def scaling_series() -> list[Series]:
        out: list[Series] = []
        for solver in dict.fromkeys(r["linear_solver"] for r in costs):
            mine = [r for r in costs if r["linear_solver"] == solver]
            xs = [_number(r["metronomes"]) for r in mine]
            out.append((f"{solver}: seconds", f"{solver} (e)", dict(ls="-", marker="o", ms=3),
                        xs, [_number(r["seconds"]) for r in mine]))
            out.append((f"{solver}: steps / $10^4$", f"{solver} (e)",
                        dict(ls=":", marker=".", ms=4), xs,
                        [_number(r["steps"]) / 1e4 for r in mine]))
        return out

    drawn = {title: scaling_series() if title == cost else series_of(title)
             for _, title in panels}
    # A long legend (section (f): presets, integrators, AUTO's points) beside its own panel;
    # the others' entries pooled into one legend, a colour per family throughout.
    own = [t for _, t in panels if len({s[0] for s in drawn[t]}) > 6]
    shared = [t for _, t in panels if t not in own]
    colours: dict[str, Any] = {}

    def colour(group: str, key: str) -> Any:
        if key == "AUTO-07p":
            return "black"
        mine = colours.setdefault(group, {})
        if key not in mine:
            mine[key] = f"C{len(mine) % 10}"
        return mine[key]

    # Rows of slots: the pooled panels two a row, the pooled legend in the slot beside an odd
    # last one or in a row of its own below them; then each long-legend panel with its legend.
    slots: list[list[str]] = [shared[i:i + 2] for i in range(0, len(shared), 2)]
    legend_row = None
    if shared:
        if len(shared) % 2:
            slots[-1].append("legend")
        else:
            slots.append(["legend"])
            legend_row = len(slots) - 1
    for title in own:
        slots.append([title, f"legend {title}"])
    pooled_labels = list(dict.fromkeys(s[0] for t in shared for s in drawn[t]))
    legend_lines = (len(pooled_labels) + 1) // 2
    heights = [0.2 + 0.17 * legend_lines if i == legend_row else 2.4 for i in range(len(slots))]
    fig = plt.figure(figsize=(BENCH_WIDTH, sum(heights)), layout="constrained")
    grid = fig.add_gridspec(len(slots), 2, height_ratios=heights)
    axes: dict[str, Any] = {}
    for i, row in enumerate(slots):
        for j, what in enumerate(row):
            axes[what] = fig.add_subplot(grid[i, :] if what == "legend" and len(row) == 1
                                         else grid[i, j])
    handles: dict[str, dict[str, Any]] = {}
    for code, title in panels:
        ax = axes[title]
        group = "shared" if title in shared else title
        mine = handles.setdefault(group, {})
        for label, key, style, xs, ys in drawn[title]:
            style = dict(style)
            style.setdefault("color", colour(group, key))
            if style.get("mfc") == "white":
                style["mec"] = style["color"]
            line, = ax.loglog(xs, ys, label=label, gid=f"series {label}", **style)
            mine.setdefault(label, line)
        _two_decades(ax)
        if title == cost:
            # The numbers of metronomes themselves on the axis (2, 4, ..., 64).
            from matplotlib.ticker import FixedLocator, NullLocator  # type: ignore[import]
            counts = sorted({int(_number(r["metronomes"])) for r in costs})
            ax.set_xlim(counts[0] / 1.15, counts[-1] * 1.15)
            ax.xaxis.set_major_locator(FixedLocator(counts))
            ax.xaxis.set_major_formatter(lambda v, _: f"{v:g}")
            ax.xaxis.set_minor_locator(NullLocator())
            ax.set_xlabel("metronomes")
            ax.set_ylabel("one period with the monodromy")
        else:
            ax.set_xlabel("run time (s; sympathy's CPU time)" if code == "f" else "run time (s)")
            ax.set_ylabel("largest error in k (relative)" if code == "f" else
                          "error in k (relative)" if code == "c" else "largest multiplier error")
        ax.set_title(textwrap.fill(title, 48))
        ax.grid(alpha=0.3, which="both")
        ax.tick_params(which="both", labelsize=8)
        _finish(ax, legend=False)
    for name, ax in axes.items():
        if not name.startswith("legend"):
            continue
        ax.axis("off")
        group = "shared" if name == "legend" else name.removeprefix("legend ")
        entries = handles.get(group, {})
        spans = ax.get_subplotspec().colspan
        ax.legend(list(entries.values()), list(entries.keys()), fontsize=8, frameon=False,
                  loc="center" if len(spans) == 2 else "center left",
                  ncol=2 if len(spans) == 2 else 1, handlelength=2.0)
    first = axes[panels[0][1]]
    return first


def kind_of(result: Any) -> str:
    """What a result is, for `draw`: "branch", "equilibria", "curve", "study", "map", "basins"
    or "simulation"."""
    kind = getattr(result, "kind", "")
    if kind in ("branch", "equilibria", "curve", "study", "map", "basins"):
        return kind
    if hasattr(result, "orbits") and hasattr(result, "first"):
        return "map"
    if hasattr(result, "branches") and hasattr(result, "parameter"):
        return "study"
    if hasattr(result, "t") and hasattr(result, "states"):
        return "simulation"
    points = getattr(result, "points", None)
    if points is not None and hasattr(points, "first") and hasattr(points, "second"):
        return "curve"
    if points is not None and hasattr(points, "eigenvalues"):
        return "equilibria"
    if points is not None and hasattr(points, "value"):
        return "branch"
    raise TypeError("plot: expected a branch, equilibria, a curve or a simulation")


def draw(result: Any, ax: Any = None, out: Optional[str] = None, **options: Any) -> Any:
    """The figure of a branch, equilibria, a curve, a study or a simulation (a function's result
    or one read by ``sympathy.load``), on `ax` or a new figure; written to `out` if given (by its
    extension). Returns the axes."""
    kind = kind_of(result)
    if kind == "study":
        ax = study(result, ax, **options)
    elif kind == "map":
        ax = stability_map(result, ax, **options)
    elif kind == "basins":
        ax = basins(result, ax, **options)
    elif kind in ("branch", "equilibria"):
        ax = branch(result, ax, **options)
    elif kind == "curve":
        ax = curve(result, ax, **options)
    else:
        ax = simulation(result, ax, **options)
    if out:
        save(ax.figure, out)
    return ax
