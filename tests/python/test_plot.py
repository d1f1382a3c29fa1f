"""The plotting module (sympathy.plot) checked by what it drew, not only that a file exists: the
stability changes at the located events (the lines' data), no two event labels overlapping and
all inside the axes (matplotlib's extents), every basins state visible with its intervals only
where it won, the bench figure's width and text sizes, and the formats by extension. Every figure
is closed after its test."""

import os
import subprocess

import matplotlib  # type: ignore[import]

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # type: ignore[import]  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import sympathy  # noqa: E402
import sympathy.plot  # noqa: E402

SOURCE = os.environ.get("SYMPATHY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "../.."))
ROW2 = os.path.join(SOURCE, "cases/row2.toml")
ABC = os.path.join(SOURCE, "cases/examples/abc.toml")


@pytest.fixture(autouse=True)
def close_figures():
    """Every figure a test drew closed after it (pyplot keeps them, and warned past 20)."""
    yield
    plt.close("all")


def runs(ax):
    """(stable, x, y) of each line the branch was drawn with, in order."""
    return [(line.get_gid() == "stable", np.asarray(line.get_xdata()), np.asarray(line.get_ydata()))
            for line in ax.get_lines() if line.get_gid() in ("stable", "unstable")]


def labels_apart(ax):
    ax.figure.canvas.draw()
    renderer = ax.figure.canvas.get_renderer()
    inside = ax.get_window_extent(renderer)
    boxes = [t.get_window_extent(renderer) for t in ax.texts if t.get_gid() == "event label"]
    for i, a in enumerate(boxes):
        assert inside.x0 <= a.x0 and a.x1 <= inside.x1 and inside.y0 <= a.y0 and a.y1 <= inside.y1
        for b in boxes[i + 1:]:
            assert not a.overlaps(b), (a, b)
    return len(boxes)


@pytest.fixture(scope="module")
def in_phase():
    # Fig. 8's in-phase branch: stable up to its NS pair at k = 84.93 and 85.01 (two events
    # between the same two computed points, 0.08 apart on a range of 99).
    return sympathy.continue_branch(ROW2, start="in-phase", param="k", from_=1, to=100,
                                    accuracy="fast")


def test_stability_changes_at_the_located_event_not_at_a_computed_point(in_phase):
    ax = in_phase.plot(y="phase:th2")
    drawn = runs(ax)
    assert [s for s, _, _ in drawn] == [True, False]
    first_ns = min(e.value for e in in_phase.events if e.type == "NS")
    # The stable run ends, and the unstable one starts, exactly at the NS point's k.
    assert drawn[0][1][-1] == first_ns and drawn[1][1][0] == first_ns
    assert not np.any(np.isclose(in_phase.points.value, first_ns, rtol=0, atol=1e-3))
    # Every point of the branch is on the lines (nothing dropped): the runs' x are the points'
    # plus the event's, twice.
    xs = np.concatenate([x for _, x, _ in drawn])
    assert len(xs) == len(in_phase.points.value) + 2


def test_close_event_labels_do_not_overlap_and_stay_inside(in_phase):
    ax = sympathy.plot.draw(in_phase, y="phase:th2")
    assert labels_apart(ax) == 2
    # The anti-phase branch's three events, the equilibria's too.
    anti = sympathy.continue_branch(ROW2, start="anti-phase", param="k", from_=1, to=100,
                                    accuracy="fast")
    assert labels_apart(anti.plot(y="phase:th2")) == len(anti.events) >= 3
    eq = sympathy.equilibria(ABC, param="p1", from_=0, to=0.4)
    ax = eq.plot()
    assert labels_apart(ax) == len(eq.events)
    for stable, x, _ in runs(ax):
        pass  # drawn; its stability changes are at its events (below)
    changes = [x[-1] for _, x, _ in runs(ax)[:-1]]
    assert all(any(e.value == c for e in eq.events) for c in changes)


def test_formats_by_extension_and_loaded_results(in_phase, tmp_path):
    for ext, magic in ((".pdf", b"%PDF"), (".svg", b"<?xml"), (".png", b"\x89PNG")):
        out = tmp_path / f"branch{ext}"
        in_phase.plot(out=str(out))
        assert out.read_bytes().startswith(magic)
    with pytest.raises(ValueError, match="expected a .pdf, .svg or .png file"):
        in_phase.plot(out=str(tmp_path / "branch.jpg"))
    # A result read back from the program's JSON draws the same lines.
    cli = os.environ.get("SYMPATHY_CLI", os.path.join(SOURCE, "build/cases/sympathy"))
    subprocess.run([cli, "continue", ROW2, "--start", "in-phase", "--param", "k", "--from", "1",
                    "--to", "100", "--accuracy", "fast", "--json", str(tmp_path / "in.json")],
                   check=True, capture_output=True)
    loaded = runs(sympathy.load(tmp_path / "in.json").plot(y="phase:th2"))
    computed = runs(in_phase.plot(y="phase:th2"))
    assert len(loaded) == len(computed)
    for (s1, x1, y1), (s2, x2, y2) in zip(loaded, computed):
        assert s1 == s2 and np.array_equal(x1, x2) and np.array_equal(y1, y2)
    run = sympathy.Case(ROW2).simulate(start="anti-phase", t_end=2)
    ax = run.plot(states=["th1", "th2"])
    assert [line.get_label() for line in ax.get_lines()] == [r"$\theta_{1}$", r"$\theta_{2}$"]


def test_curve_in_its_two_parameters():
    curve = sympathy.curve(ROW2, start="anti-phase", param="k", from_=44, to=50, event="BP1",
                           second="c", second_from=0.0, second_to=0.5, accuracy="fast")
    ax = curve.plot()
    line = next(line for line in ax.get_lines() if line.get_gid() == "curve")
    assert np.array_equal(line.get_xdata(), curve.points.first)
    assert ax.get_xlabel() == "k (N/m)" and ax.get_ylabel() == "c (N s/m)"


def test_study_diagram_of_a_two_way_branch(tmp_path):
    # A branch found at k = 48 and followed both ways (its points' indices negative on the
    # backward part, events placed after them): each marker on its branch's line, the stability
    # changing at the events, every label apart.
    study = tmp_path / "two_way.toml"
    study.write_text(f"""title = "two ways"
case = "{ROW2}"
params = "table2"
parameter = "k"
axis = "frequency"

[[branches]]
name = "anti-phase"
start = "anti-phase"
from = 30.0
to = 70.0
at = 48.0
""")
    result = sympathy.study(str(study), out=str(tmp_path), accuracy="fast")
    branch = result.branches["anti-phase"]
    assert min(branch.points.index) < 0 and len(branch.events) >= 3
    ax = result.plot()
    assert labels_apart(ax) == len(branch.events)
    x = np.asarray(branch.points.value)
    f = np.asarray(branch.points.frequency)
    order = np.argsort(x)
    for line in ax.get_lines():
        if str(line.get_gid()).startswith("event "):
            for mx, my in zip(line.get_xdata(), line.get_ydata()):
                assert abs(my - np.interp(mx, x[order], f[order])) < 1e-3
    ends = [xs[-1] for _, xs, _ in runs(ax)[:-1]]
    assert all(any(e.value == end for e in branch.events) for end in ends)


def test_the_plot_script_draws_an_equation_case_files_branch_and_curve(tmp_path):
    # scripts/plot on the program's JSON of abc's family born at HB1 (an equation case file):
    # a vector file, drawn by the same module (its two folds at AUTO's p1 = 0.211903 and 0.213697).
    cli = os.environ.get("SYMPATHY_CLI", os.path.join(SOURCE, "build/cases/sympathy"))
    subprocess.run([cli, "continue", ABC, "--param", "p1", "--from", "0.2", "--to", "0.25",
                    "--switch-at", "HB1", "--json", str(tmp_path / "family.json")],
                   check=True, capture_output=True)
    env = dict(os.environ, SYMPATHY_BUILD_DIR=os.path.dirname(os.path.dirname(
        os.path.dirname(sympathy.__file__))))
    run = subprocess.run([os.path.join(SOURCE, "scripts/plot"), str(tmp_path / "family.json"),
                          "--y", "u1", "--out", str(tmp_path / "family.svg")],
                         check=True, capture_output=True, text=True, env=env)
    assert run.stdout.strip().endswith("family.svg")
    assert (tmp_path / "family.svg").read_text().lstrip().startswith("<?xml")
    ax = sympathy.load(tmp_path / "family.json").plot(y="u1")
    folds = sorted(round(e.value, 6) for e in sympathy.load(tmp_path / "family.json").events
                   if e.type == "LP")
    assert folds == [0.211903, 0.213697]
    assert labels_apart(ax) >= 2
    # The family's first fold followed in (p1, p3), drawn from the command line and from Python:
    # the curve's line is its points (about 2 s).
    subprocess.run([cli, "curve", ABC, "--parent", str(tmp_path / "family.json"), "--event", "LP1",
                    "--param", "p1", "--from", "0.15", "--to", "0.3", "--second", "p3",
                    "--second-from", "1.4", "--second-to", "1.6", "--quiet",
                    "--json", str(tmp_path / "fold.json")], check=True, capture_output=True)
    run = subprocess.run([os.path.join(SOURCE, "scripts/plot"), str(tmp_path / "fold.json"),
                          "--out", str(tmp_path / "fold.pdf")],
                         check=True, capture_output=True, text=True, env=env)
    assert run.stdout.strip().endswith("fold.pdf")
    assert (tmp_path / "fold.pdf").read_bytes().startswith(b"%PDF")
    fold = sympathy.load(tmp_path / "fold.json")
    ax = fold.plot()
    line = next(line for line in ax.get_lines() if line.get_gid() == "curve")
    assert np.array_equal(line.get_xdata(), fold.points.first)
    assert (ax.get_xlabel(), ax.get_ylabel()) == ("$p_{1}$", "$p_{3}$")


def test_stability_map_has_a_legend_entry_per_curve_kind_and_labels_apart(tmp_path):
    # A small map of the anti-phase orbit in k and c (its BP and two NS curves): each curve
    # kind in the legend, the codimension-two and mark labels apart, the shading from its grid.
    (tmp_path / "small.toml").write_text(f"""title = "small"
case = "{ROW2}"
params = "table2"
marks = ["table2"]

[first]
parameter = "k"
from = 10.0
to = 60.0
points = 6

[second]
parameter = "c"
from = 0.0
to = 0.05
points = 4

[[orbits]]
name = "anti-phase"
start = "anti-phase"
""")
    result = sympathy.map(tmp_path / "small.toml", out=str(tmp_path), accuracy="fast")
    for m in (result, sympathy.load(tmp_path / "small.json")):
        ax = m.plot()
        legend = [t.get_text() for t in ax.get_legend().get_texts()]
        kinds = {c.kind for c in m.orbits[0].curves}
        assert kinds == {"BP", "NS"} and all(f"{k} curve" in legend for k in kinds)
        assert labels_apart(ax) == 1  # table2's star
        assert [image.get_gid() for image in ax.images] == ["shading"]


def shade_at(ax, x, y):
    """The colour the map's shading has at the point (x, y) of its two parameters."""
    image = next(image for image in ax.images if image.get_gid() == "shading")
    x0, x1, y0, y1 = image.get_extent()
    codes = image.get_array()
    rows, cols = codes.shape
    col = min(int((x - x0) / (x1 - x0) * cols), cols - 1)
    row = min(int((y - y0) / (y1 - y0) * rows), rows - 1)
    return tuple(image.to_rgba(codes)[row, col])


def test_map_shading_agrees_with_its_curves_on_both_sides(tmp_path):
    # A map's JSON whose curves are known exactly (k in [0, 10], c in [0, 1], a 6 x 5 grid):
    # a BP line at k = 4.3 (one multiplier outside to its right), an NS line c = 0.8 - 0.04 k
    # (a pair outside above it; a neutral saddle for k > 8, which changes no stability) and an
    # LP line at k = 9.1 (no orbit beyond). The grid's cells change at k = 5 and c = 0.625 or
    # 0.875, so points 0.06 in k or 0.02 in c from a curve were shaded wrong by the grid's cells;
    # shaded by the regions the curves bound, each side is its own.
    import json

    def count(k, c):
        if k > 9.1:
            return -1
        return int(k > 4.3) + 2 * int(c > 0.8 - 0.04 * k)

    def line(ks, cs, saddle=lambda k: False):
        return [{"first": float(k), "second": float(c), "neutral_saddle": bool(saddle(k))}
                for k, c in zip(ks, cs)]

    first, second = [0.0, 2.0, 4.0, 6.0, 8.0, 10.0], [0.0, 0.25, 0.5, 0.75, 1.0]
    ns_k = np.linspace(0.0, 9.1, 92)
    orbit = {"name": "synthetic", "start": "anti-phase",
             "grid": {"first": first, "second": second,
                      "unstable_count": [[count(k, c) for k in first] for c in second]},
             "curves": [
                 {"kind": "BP", "points": line([4.3] * 11, np.linspace(0, 1, 11)), "events": []},
                 {"kind": "NS", "points": line(ns_k, 0.8 - 0.04 * ns_k, lambda k: k > 8.0),
                  "events": [{"type": "R4", "first": 2.0, "second": 0.72},
                             {"type": "R3", "first": 2.1, "second": 0.716}]},
                 {"kind": "LP", "points": line([9.1] * 11, np.linspace(0, 1, 11)), "events": []}]}
    (tmp_path / "synthetic.json").write_text(json.dumps({
        "map": "synthetic", "title": "", "case": "none", "marks": [], "orbits": [orbit],
        "first": {"parameter": "k", "from": 0.0, "to": 10.0},
        "second": {"parameter": "c", "from": 0.0, "to": 1.0}}))
    ax = sympathy.plot.draw(sympathy.load(tmp_path / "synthetic.json"))
    from matplotlib.colors import to_rgba  # type: ignore[import]
    shades = [to_rgba(c) for c in sympathy.plot.REGION_SHADES]

    def expected(k, c):
        n = count(k, c)
        return shades[sympathy.plot.REGION_NO_ORBIT if n < 0 else
                      sympathy.plot.REGION_STABLE if n == 0 else sympathy.plot.REGION_UNSTABLE]

    samples = [(4.3 + side, c) for c in (0.1, 0.3, 0.5, 0.9) for side in (-0.06, 0.06)]
    samples += [(k, 0.8 - 0.04 * k + side) for k in (0.5, 1.5, 3.0, 4.0, 6.0)
                for side in (-0.02, 0.02)]
    samples += [(9.1 + side, c) for c in (0.2, 0.6) for side in (-0.06, 0.06)]
    for k, c in samples:
        assert shade_at(ax, k, c) == expected(k, c), (k, c)
    assert shade_at(ax, 4.24, 0.1) == shades[sympathy.plot.REGION_STABLE]  # both states are drawn
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert {"BP curve", "NS curve", "NS: neutral saddle", "LP curve"} <= set(legend)
    assert labels_apart(ax) == 2  # R4 and R3, 0.1 apart in k


# Shares of the docs' basins study (cases/figures/basins_k.toml, 20 starts a point; the shares
# docs/guides/basins.md quotes), on four of its grid points, with the two mirror-image locked
# states at exactly the same shares (0.25 at k = 45), as that study found them.
BASINS_SHARES = {40.0: {"in-phase": 20},
                 45.0: {"in-phase": 10, "locked+2.95": 5, "locked-2.95": 5},
                 50.0: {"in-phase": 8, "not-synchronized": 12},
                 55.0: {"not-synchronized": 20},
                 60.0: {"anti-phase": 20}}
BASINS_STATES = ["in-phase", "anti-phase", "locked+2.95", "locked-2.95", "not-synchronized"]


def wilson(count, n):
    """The 95% Wilson score interval of count / n (z = 1.959964), as the program writes it."""
    z, p = 1.959964, count / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * np.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    return max(0.0, centre - half), min(1.0, centre + half)


def basins_json(tmp_path, grid=None):
    """A basins JSON as the program writes it (the keys sympathy.load and the plot read), with
    its runs CSV beside it: per grid point each state's count, share and interval."""
    import json
    points, runs = [], ["task,point,k,start,th1_0,th2_0,class"]
    for i, (k, counts) in enumerate(BASINS_SHARES.items()):
        shares = {}
        for state in BASINS_STATES:
            n = counts.get(state, 0)
            lower, upper = wilson(n, 20)
            shares[state] = {"count": n, "share": n / 20, "lower": lower, "upper": upper}
        points.append({"point": i, "values": {"k": k}, "runs": 20, "shares": shares})
        classes = [s for s, n in counts.items() for _ in range(n)]
        for j, state in enumerate(classes):
            runs.append(f"{20 * i + j},{i},{k},{j},{-0.6 + 0.06 * j},{0.6 - 0.05 * j},{state}")
    (tmp_path / "basins_runs.csv").write_text("\n".join(runs) + "\n")
    (tmp_path / "basins.json").write_text(json.dumps({
        "study": "", "title": "synthetic", "case": "cases/row2.toml", "params": "table2",
        "grid": grid or [{"parameter": "k", "from": 40.0, "to": 60.0, "count": 5}],
        "starts": 20, "angles": [-0.6, 0.6], "initial": {}, "t_end": 100.0, "complete": True,
        "runs_csv": "basins_runs.csv", "points": points}))
    return sympathy.load(tmp_path / "basins.json")


def test_basins_every_state_visible_and_no_interval_at_a_zero_share(tmp_path):
    # Each state that won a run has its markers at exactly its shares, where it won; none is
    # hidden under another (locked+2.95 and locked-2.95 have the same shares: drawn side by
    # side, each marker at least its own size from every other state's, in the file's pixels);
    # an interval only where the state won (its bar from the Wilson lower to the upper bound),
    # none at a zero share; its line through its markers down to 0 at the neighbouring points.
    result = basins_json(tmp_path)
    ax = sympathy.plot.basins(result)
    ax.figure.canvas.draw()
    won = list(dict.fromkeys(s for c in BASINS_SHARES.values() for s in c))  # in order met
    markers = {line.get_gid(): line for line in ax.get_lines() if line.get_gid() in won}
    assert set(markers) == set(won)
    ks = np.array(list(BASINS_SHARES))
    for state, line in markers.items():
        wins = [k for k, counts in BASINS_SHARES.items() if counts.get(state, 0) > 0]
        x, y = np.asarray(line.get_xdata()), np.asarray(line.get_ydata())
        assert np.allclose(x, wins, atol=0.5) and len(x) == len(wins)
        assert np.array_equal(y, [BASINS_SHARES[k][state] / 20 for k in wins])
        # The intervals: one bar a won point, at its marker, from lower to upper; none else.
        bars = [c for c in ax.containers if c.lines[2] and
                c.lines[2][0].get_gid() == f"interval {state}"]
        segments = [seg for c in bars for seg in c.lines[2][0].get_segments()]
        assert len(segments) == len(wins)
        for seg, k, xk in zip(segments, wins, x):
            lower, upper = wilson(BASINS_SHARES[k][state], 20)
            assert seg[0][0] == seg[1][0] == xk
            assert np.allclose(sorted([seg[0][1], seg[1][1]]), [lower, upper])
        # The line: through the won points and down to 0 at their neighbours, nothing else.
        path = next(line for line in ax.get_lines() if line.get_gid() == f"line {state}")
        drawn = ~np.isnan(np.asarray(path.get_ydata(), dtype=float))
        near = np.array([any(abs(k - w) <= 5.0 for w in wins) for k in ks])
        assert np.array_equal(drawn, near)
    assert "anti-phase" in markers  # won only at the last point
    # None hidden: every two markers of different states at least a marker's size apart (or
    # of different shapes and still apart) in display coordinates.
    size = {state: line.get_markersize() * ax.figure.dpi / 72.0 for state, line in
            markers.items()}
    xy = {state: line.get_transform().transform(np.column_stack([line.get_xdata(),
                                                                 line.get_ydata()]))
          for state, line in markers.items()}
    for a in won:
        for b in won:
            if a < b:
                d = np.hypot(*(xy[a][:, None, :] - xy[b][None, :, :]).transpose(2, 0, 1))
                assert d.min() >= 0.9 * max(size[a], size[b]), (a, b, d.min())
    assert markers["locked+2.95"].get_marker() != markers["locked-2.95"].get_marker()
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert legend == won


def test_basins_with_a_study_below_a_point_s_starts_and_two_parameters(tmp_path):
    # --study: the shares above Fig. 8's diagram on the same axis (k 35 to 65: the grid's half a
    # step beyond its ends); --map POINT: every run's start angles, by the state it ended in;
    # a two-parameter grid: a map of the share per state.
    result = basins_json(tmp_path)
    study = sympathy.study(os.path.join(SOURCE, "cases/figures/fig08.toml"), out=str(tmp_path),
                           accuracy="fast")
    ax = sympathy.plot.basins(result, study=study)
    top, bottom = ax.figure.axes[:2]
    assert top is ax and top.get_xlim() == bottom.get_xlim() == (37.5, 62.5)
    assert {line.get_gid() for line in bottom.get_lines()} >= {"stable", "unstable"}
    with pytest.raises(ValueError, match="expected k, the basins grid's"):
        sympathy.plot.basins(result, study=sympathy.Result(parameter="c", branches={}))
    ax = result.plot(point=2)  # k = 50: 8 in phase, 12 not synchronized
    drawn = {line.get_gid(): len(line.get_xdata()) for line in ax.get_lines()}
    assert drawn == {"in-phase": 8, "not-synchronized": 12}
    with pytest.raises(ValueError, match="expected a grid point 0 .. 4"):
        result.plot(point=5)
    two = basins_json(tmp_path, grid=[{"parameter": "k", "from": 40.0, "to": 60.0, "count": 5},
                                      {"parameter": "c", "value": 0.0185}])
    for p in two.points:
        p.values["c"] = 0.0185
    ax = sympathy.plot.basins(two)
    images = {image.get_gid(): image.get_array() for a in ax.figure.axes for image in a.images}
    assert set(images) == {f"share {s}" for s in BASINS_STATES if s != "anti-phase"} | \
        {"share anti-phase"}
    assert np.allclose(images["share in-phase"][0], [1.0, 0.5, 0.4, 0.0, 0.0])


def bench_rows():
    """A bench report's rows (bench.csv's columns that the figure reads): sections (a), (c) and
    (f), (f) with presets, a sweep, a failed run and AUTO-07p's points."""
    rows = []

    def row(problem, setting, rtol, error, seconds, converged="yes", cpu=""):
        key = "parameter_error" if problem[1] in "cf" else "multiplier_error"
        rows.append({"problem": problem, "setting": setting, "rtol": rtol, "seconds": seconds,
                     "multiplier_error": "-", "parameter_error": "-", key: error,
                     "converged": converged, "cpu_seconds": cpu})

    for problem in ("(a) anti-phase orbit, Table II",
                    "(c) first stability change of the anti-phase k-branch"):
        for family, scale in (("BDF, dense, model derivatives", 1.0), ("Adams", 0.5),
                              ("BDF, KLU", 2.0)):
            for rtol, error, seconds in (("1e-06", "1e-5", "0.01"), ("1e-09", "1e-8", "0.02"),
                                         ("1e-12", "1e-11", "0.05")):
                row(problem, family, rtol, error, str(scale * float(seconds)))
    f = "(f) anti-phase k-branch, k 1 to 100 N/m"
    for n, preset in enumerate(("fast", "default", "high", "fast, whole state",
                                "default, whole state")):
        row(f, f"preset {preset}", "1e-08", str(10.0 ** -(8 + n)), "9.9", cpu=str(0.1 * (n + 1)))
    for n, family in enumerate(("forward module, BDF", "forward module, Adams",
                                "augmented, Adams", "ERK Dormand-Prince")):
        row(f, family, "1e-10", "1e-9", "9.9", cpu=str(0.2 + n / 10))
        row(f, family, "1e-12", "1e-11", "9.9", cpu=str(0.4 + n / 10))
    row(f, "ERK Verner", "1e-07", "-", "9.9", converged="no", cpu="1.0")
    for ntst in (25, 50, 100):
        row(f, f"AUTO-07p NTST {ntst}", "-", "4e-7", str(ntst / 100), converged="AUTO-07p")
    scaling = [{"metronomes": str(n), "linear_solver": solver, "steps": str(1000 * n),
                "seconds": str(0.001 * n * n)} for solver in ("dense", "structured")
               for n in (2, 4, 8, 16)]
    return rows, scaling


def test_bench_is_readable_at_a_page_width():
    # The accuracy report a page wide (7 inches), two panels a row, no text under 8 points at
    # that size (the report was five panels in a row, 3300 x 504 px, 6-point labels); each panel
    # the problem's points (section (f) on CPU seconds, AUTO's on its own seconds), a run that
    # failed left out; (f)'s long legend beside it, the others' shared.
    import matplotlib.text  # type: ignore[import]
    rows, scaling = bench_rows()
    ax = sympathy.plot.bench(rows, scaling)
    fig = ax.figure
    assert tuple(fig.get_size_inches())[0] == 7.0
    fig.canvas.draw()
    texts = [t for t in fig.findobj(matplotlib.text.Text) if t.get_visible() and t.get_text()]
    assert len(texts) > 40
    assert min(t.get_fontsize() for t in texts) >= 8.0
    panels = [a for a in fig.axes if a.axison]
    assert [a.get_title().split()[0] for a in panels] == ["(a)", "(c)", "(e)", "(f)"]
    rows_of_panels = {}
    for a in panels:
        rows_of_panels.setdefault(round(a.get_position().y0, 2), []).append(a)
    assert max(len(r) for r in rows_of_panels.values()) == 2
    # Every text inside the figure: titles, axis labels, legends and the ticks in view.
    renderer = fig.canvas.get_renderer()
    shown = [t for t in texts if not any(t in a.get_xticklabels() + a.get_yticklabels()
                                         for a in fig.axes)]
    for a in panels:
        for axis in (a.xaxis, a.yaxis):
            lo, hi = sorted(axis.get_view_interval())
            shown += [tick.label1 for tick in axis.get_major_ticks() if lo <= tick.get_loc() <= hi]
    for t in shown:
        box = t.get_window_extent(renderer)
        assert fig.bbox.x0 - 1 <= box.x0 and box.x1 <= fig.bbox.x1 + 1, t.get_text()
        assert fig.bbox.y0 - 1 <= box.y0 and box.y1 <= fig.bbox.y1 + 1, t.get_text()
    f = panels[-1]
    series = {line.get_gid(): line for line in f.get_lines()}
    assert np.allclose(series["series preset fast (rtol 1e-8)"].get_xdata(), [0.1])
    assert np.allclose(series["series AUTO-07p (AUTO's measurements)"].get_xdata(),
                       [0.25, 0.5, 1.0])
    assert not any("Verner" in str(gid) for gid in series)
    assert series["series preset fast, whole state (rtol 1e-8)"].get_markerfacecolor() in \
        ("white", (1.0, 1.0, 1.0, 1.0))
    legends = [a.get_legend() for a in fig.axes if not a.axison and a.get_legend()]
    entries = [[t.get_text() for t in legend.get_texts()] for legend in legends]
    assert any("forward module, BDF" in e for e in entries)
    assert any("BDF, KLU" in e and "structured: seconds" in e for e in entries)
    # Section (f) alone: one panel and its legend, the figure still a page wide.
    ax = sympathy.plot.bench(rows, scaling, sections="f")
    assert [a.get_title().split()[0] for a in ax.figure.axes if a.axison] == ["(f)"]
    assert tuple(ax.figure.get_size_inches())[0] == 7.0


def test_phase_difference_is_the_exact_lag_and_is_drawn_below_the_angles():
    # x1 = sin(2 pi f t), x2 = sin(2 pi f t - lag): th2 - th1 is -lag, wrapped into
    # [-pi/2, 3 pi/2) (2 pi - lag for lag = 2.0); zero crossings interpolated linearly with 200
    # samples a period are exact to 1e-4 rad for a sine.
    f, lag = 1.7, 2.0
    t = np.arange(0.0, 10.0, 1.0 / (200 * f))
    run = sympathy.Result(t=t, state_names=["th1", "th2"],
                          states=np.column_stack([np.sin(2 * np.pi * f * t),
                                                  np.sin(2 * np.pi * f * t - lag)]))
    d = sympathy.plot.phase_differences(run)["th2"]
    inside = ~np.isnan(d)
    assert inside.sum() > 0.8 * len(t)
    assert np.max(np.abs(d[inside] - (2 * np.pi - lag))) < 1e-4
    ax = run.plot()
    below = [a for a in ax.figure.axes if a is not ax][0]
    line = next(line for line in below.get_lines() if line.get_gid() == "phase th2")
    assert np.array_equal(line.get_ydata(), d, equal_nan=True)


def test_time_series_layout_of_the_paper_with_the_phase_difference():
    # The row setup from close to anti-phase (the Simulation guide's run, 60 s here): three
    # panels, angles, th2 - th1 and the platform in mm; the phase panel's data are
    # phase_differences', which start at anti-phase (pi, within 0.1) and end in phase (0).
    run = sympathy.Case(ROW2).simulate(start="anti-phase", initial={"th2": -0.25}, t_end=60)
    ax = sympathy.plot.time_series(run)
    axes = ax.figure.axes
    assert len(axes) == 3
    assert [a.get_ylabel() for a in axes] == ["angle (rad)", "phase difference", "platform (mm)"]
    d = sympathy.plot.phase_differences(run)["th2"]
    line = next(line for line in axes[1].get_lines() if line.get_gid() == "phase th2")
    assert np.array_equal(line.get_ydata(), d, equal_nan=True)
    inside = d[~np.isnan(d)]
    assert abs(inside[0] - np.pi) < 0.1 and abs(inside[-1]) < 0.3


def test_fig09_marks_both_stiffnesses_and_its_labels_are_apart(tmp_path):
    # The paper's Fig. 9 (cases/figures/fig09.toml): Table III's platform, the stiffness before
    # and after the fit marked (Tables II and III: k = 14.7467 and 47.0899 N/m in
    # cases/row2.toml), a vertical line at each, named inside the axes; its in-phase branch's
    # cluster of events between k = 50 and 55 labelled with no two labels' boxes overlapping,
    # the marks' names included.
    import json
    result = sympathy.study(os.path.join(SOURCE, "cases/figures/fig09.toml"), out=str(tmp_path),
                            accuracy="fast")
    assert json.loads((tmp_path / "fig09.json").read_text())["params_set"] == "table3"
    for r in (result, sympathy.load(tmp_path / "fig09.json")):
        ax = r.plot()
        lines = {line.get_gid(): line.get_xdata()[0] for line in ax.get_lines()
                 if str(line.get_gid()).startswith("mark ")}
        assert lines == {"mark table2": 14.7467, "mark table3": 47.0899}
        events = sum(len(b.events) for b in r.branches.values())
        for t in ax.texts:
            if t.get_gid() == "mark label":
                t.set_gid("event label")  # checked with the events' labels
        assert labels_apart(ax) == events + 2 >= 8


def test_fit_figure_has_the_fitted_values_with_units_and_the_residuals():
    # sympathy.plot.fit on a made-up recording: the title's values carry their units (d in
    # N m s, s in N m, th1(0) in rad: docs/reference/case-files.md), the residual panel's data
    # are data - model, the platform's x in mm.
    t = np.linspace(0.0, 1.0, 11)
    data = {"th1": np.sin(t), "x": 1e-3 * t}
    model = {"th1": np.sin(t) + 0.01, "x": 2e-3 * t}
    unknowns = [{"name": "d", "value": 2.4e-6, "error": 6.2e-9},
                {"name": "s", "value": 4.51e-5, "error": 8.5e-8},
                {"name": "th1(0)", "value": 0.3, "error": 7.2e-4}]
    ax = sympathy.plot.fit(t, data, model, unknowns=unknowns)
    title = ax.figure._suptitle.get_text()
    assert "d = 2.4e-06" in title and "N m s" in title and "N m," in title and "rad" in title
    axes = ax.figure.axes
    residual = next(line for line in axes[1].get_lines() if line.get_gid() == "residual th1")
    assert np.allclose(residual.get_ydata(), -0.01)
    residual = next(line for line in axes[3].get_lines() if line.get_gid() == "residual x")
    assert np.allclose(residual.get_ydata(), -1e3 * 1e-3 * t)
    assert axes[2].get_ylabel() == "x (mm)"


def test_map_draws_the_equilibria_curves_beside_the_cycles(tmp_path):
    # The Bautin map (cases/examples/bautin_map.toml): the cycle's panel with its fold of cycles
    # (LP curve) and the equilibrium's Hopf line b1 = 0 (dashed, every point to 1e-9) with its GH
    # labelled; the same from sympathy.map and from the JSON read back.
    path = os.path.join(SOURCE, "cases/examples/bautin_map.toml")
    result = sympathy.map(path, out=str(tmp_path), accuracy="fast")
    for m in (result, sympathy.load(tmp_path / "bautin_map.json")):
        ax = sympathy.plot.stability_map(m)
        legend = [t.get_text() for t in ax.get_legend().get_texts()]
        assert "LP curve" in legend and "HB curve of equilibria" in legend
        hopf = [line for line in ax.lines if line.get_gid() == "curve HB of equilibria"]
        assert hopf and all(line.get_linestyle() == "--" for line in hopf)
        assert np.abs(np.concatenate([line.get_xdata() for line in hopf])).max() < 1e-9
        assert [t.get_text() for t in ax.texts if t.get_gid() == "event label"] == ["GH"]
        plt.close(ax.figure)


def test_map_of_equilibria_alone_is_one_panel_with_each_point_marked_once(tmp_path):
    # The BT normal form: its fold parabola and Hopf line both pass through the BT point, marked
    # and labelled once; no orbit, so no shading; the map's window is the axes'.
    (tmp_path / "bt.toml").write_text(f"""case = "{os.path.join(SOURCE, 'cases/examples/bt.toml')}"
[first]
parameter = "b1"
from = -0.5
to = 0.5
points = 0
[second]
parameter = "b2"
from = -1.5
to = 1.0
points = 0
[[equilibria]]
name = "rest"
""")
    result = sympathy.map(tmp_path / "bt.toml", out=str(tmp_path))
    assert sorted(c.kind for c in result.equilibria[0].curves) == ["HB", "LP"]
    for m in (result, sympathy.load(tmp_path / "bt.json")):
        ax = sympathy.plot.stability_map(m)
        assert len(ax.figure.axes) == 1 and not ax.images
        assert ax.get_xlim() == (-0.5, 0.5) and ax.get_ylim() == (-1.5, 1.0)
        assert [t.get_text() for t in ax.texts if t.get_gid() == "event label"] == ["BT"]
        legend = [t.get_text() for t in ax.get_legend().get_texts()]
        assert {"LP curve of equilibria", "HB curve of equilibria",
                "HB of equilibria: neutral saddle"} <= set(legend)
        plt.close(ax.figure)
