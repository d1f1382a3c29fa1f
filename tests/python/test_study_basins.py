"""A study's [basins] walk from Python: ``sympathy.study(...).basins`` and
``sympathy.load(STUDY.json).basins``, the same numbers as the program's CSV.

Expected numbers are closed forms (cases/examples/cycle_pitchfork.toml): the circle w = 0 wins
every start before mu = 0, the circles w = +-sqrt(mu) born at its branch point every start after.
"""

import csv
import math
import os

import matplotlib  # type: ignore[import]

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # type: ignore[import]  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import sympathy  # noqa: E402
import sympathy.plot  # noqa: E402

SOURCE = os.environ.get("SYMPATHY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "../.."))


@pytest.fixture(autouse=True)
def private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("SYMPATHY_CACHE_DIR", str(tmp_path / "cache"))


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """The pitchfork's study run from Python, its JSON read back, and the CSV's rows."""
    out = tmp_path_factory.mktemp("walk")
    os.environ["SYMPATHY_CACHE_DIR"] = str(out / "cache")
    study = os.path.join(SOURCE, "cases/examples/cycle_pitchfork_study.toml")
    result = sympathy.study(study, out=str(out))
    loaded = sympathy.load(out / "cycle_pitchfork_study.json")
    rows = list(csv.DictReader(open(out / "cycle_pitchfork_study-basins.csv")))
    return result, loaded, rows


def test_the_walk_from_python_and_from_its_json(walk):
    result, loaded, rows = walk
    for walk in (result.basins, loaded.basins):
        np.testing.assert_allclose(walk.values, [-0.25, -0.15, -0.05, 0.05, 0.15, 0.25],
                                   atol=1e-15)
        after = walk.values > 0
        np.testing.assert_array_equal(walk.shares["circle"].share, np.where(after, 0.0, 1.0))
        pair = [s for s in walk.shares.values() if s.branch == "pair"]
        assert len(pair) == 2
        np.testing.assert_array_equal(pair[0].share + pair[1].share, np.where(after, 1.0, 0.0))
        for value, attractors in zip(walk.values, walk.attractors):
            for a in attractors:
                if a.branch == "pair":
                    assert abs(abs(a.state[2]) - math.sqrt(value)) < 1e-8
        # When each share's runs were certified: every run is, so the quartiles are numbers
        # where the share is not zero and NaN where it is.
        circle = walk.shares["circle"]
        assert circle.certified_median.dtype == float
        np.testing.assert_array_equal(np.isnan(circle.certified_median), circle.count == 0)
        assert np.all(circle.certified_q1[~after] <= circle.certified_q3[~after])
        assert [c.name for c in walk.changes] == ["circle", "pair (1)", "pair (2)"]
        assert all(c.events[0].type == "BP" and abs(c.events[0].parameter) < 1e-8
                   for c in walk.changes)
        # The CSV's counts, row by row.
        expected = [(j, name, share.count[j]) for j in range(len(walk.values))
                    for name, share in walk.shares.items()]
        assert len(rows) == len(expected)
        for r, (j, name, count) in zip(rows, expected):
            assert abs(float(r["value"]) - walk.values[j]) < 1e-12
            assert (r["attractor"], int(r["count"])) == (name, count)


def test_the_shares_drawn_above_the_diagram(walk):
    """plot.study: the shares panel above the branches', a curve per attractor, the BP where the
    pair appears as a dotted line at mu = 0; the branches (no pendula) by the maximum of w."""
    result = walk[0]
    top = sympathy.plot.study(result)
    fig = top.figure
    assert len(fig.axes) == 2
    shares = {line.get_gid(): line for line in top.get_lines()
              if (line.get_gid() or "").startswith("share ")}
    assert set(shares) == {"share circle", "share pair (1)", "share pair (2)"}
    np.testing.assert_array_equal(shares["share circle"].get_ydata(), [1, 1, 1, 0, 0, 0])
    changes = [line for line in top.get_lines() if line.get_gid() == "change BP"]
    assert len(changes) == 1 and abs(changes[0].get_xdata()[0]) < 1e-8
    assert fig.axes[1].get_ylabel() == "max of w"
    with pytest.raises(ValueError, match="two panels; no ax"):
        sympathy.plot.study(result, ax=top)
    plt.close("all")


def test_a_study_without_basins_has_none(tmp_path):
    (tmp_path / "s.toml").write_text(
        f'case = "{os.path.join(SOURCE, "cases/examples/cycle_pitchfork.toml")}"\n'
        'parameter = "mu"\n[[branches]]\nname = "circle"\nfrom = -0.3\nto = -0.1\n')
    assert sympathy.study(str(tmp_path / "s.toml"), out=str(tmp_path / "out")).basins is None
