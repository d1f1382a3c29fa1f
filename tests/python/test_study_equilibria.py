"""A study's [[equilibria]] entries from Python: ``sympathy.study(...).equilibria`` and
``sympathy.load(STUDY.json).equilibria`` (dicts by name), and their panel in the study's figure.

Expected numbers are closed forms: the transcritical normal form x' = p x - x^2 has the branch
point p = 0 on x = 0 and the born branch x = p; the Hopf normal form (w = 2) its Hopf point at
mu = 0, stable below it, unstable above.
"""

import os
import subprocess

import matplotlib  # type: ignore[import]

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # type: ignore[import]  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import sympathy  # noqa: E402
import sympathy.plot  # noqa: E402

TRANSCRITICAL = """kind = "equations"
name = "transcritical"
[states]
x = 0.0
y = 0.0
[parameters]
p = -0.5
[equations]
x = "p*x - x^2"
y = "-y"
"""

HOPF = """kind = "equations"
name = "hopf2"
[states]
x = 0.0
y = 0.0
[parameters]
mu = -0.5
w = 2.0
[intermediates]
r2 = "x^2 + y^2"
[equations]
x = "mu*x - w*y - x*r2"
y = "w*x + mu*y - y*r2"
"""


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def transcritical(tmp_path_factory):
    """The transcritical study: its result from sympathy.study and its JSON read back."""
    d = tmp_path_factory.mktemp("tc")
    (d / "transcritical.toml").write_text(TRANSCRITICAL)
    (d / "tc.toml").write_text("""title = "Transcritical normal form"
case = "transcritical.toml"
parameter = "p"

[[equilibria]]
name = "trivial"
from = -0.5
to = 0.5

[[equilibria]]
name = "born"
from = -0.5
to = 0.5
switch_at = "trivial:BP1"
""")
    result = sympathy.study(str(d / "tc.toml"), out=str(d / "out"))
    return result, sympathy.load(d / "out" / "tc.json")


def test_study_equilibria_by_name(transcritical):
    result, _ = transcritical
    assert list(result.equilibria) == ["trivial", "born"] and result.branches == {}
    assert result.equilibria_axis == "x"  # the first state by default
    trivial, born = result.equilibria["trivial"], result.equilibria["born"]
    assert trivial.error == "" and born.error == ""
    # The BP at p = 0 (1e-8) on x = 0, the born branch on x = p (1e-8) across the window.
    assert [e.type for e in trivial.events] == ["BP"] and abs(trivial.events[0].value) < 1e-8
    x = np.asarray(born.points.state)[:, 0]
    assert np.max(np.abs(x - born.points.value)) < 1e-8
    assert min(born.points.value) == -0.5 and max(born.points.value) == 0.5


def test_load_reads_the_same_equilibria(transcritical):
    result, loaded = transcritical
    assert loaded.kind == "study" and list(loaded.equilibria) == ["trivial", "born"]
    for name, e in result.equilibria.items():
        back = loaded.equilibria[name]
        # JSON keeps every double's digits: the arrays are equal, not close.
        assert np.array_equal(back.points.value, e.points.value)
        assert np.array_equal(back.points.state, e.points.state)
        assert [x.type for x in back.events] == [x.type for x in e.events]
        assert back.csv == f"tc-{name}.csv" and not hasattr(back, "error")


def test_equilibria_alone_drawn_in_one_panel(transcritical):
    result, loaded = transcritical
    for study in (result, loaded):
        ax = sympathy.plot.study(study)
        assert len(ax.figure.axes) == 1 and ax.get_ylabel() == "x (equilibria)"
        # x = 0 stable below the BP, x = p above it: solid runs where p < 0 on the first, p > 0
        # on the born one. The first changes at its located BP; the born branch, which starts at
        # the BP and does not report it again, half way between its points there (0.007 apart).
        lines = [(line.get_gid(), np.asarray(line.get_xdata()), np.asarray(line.get_ydata()))
                 for line in ax.get_lines() if line.get_gid() in ("stable", "unstable")]
        assert len(lines) == 4
        for gid, xs, ys in lines:
            inside = np.abs(xs) > 0.01
            assert np.all((xs[inside] < 0) == (gid == "stable")) or \
                np.all((xs[inside] > 0) == (gid == "stable"))
        assert any(str(line.get_gid()) == "event BP" for line in ax.get_lines())
        assert any(t.get_text().startswith("BP ") for t in ax.texts)


def test_branches_above_equilibria_below(tmp_path):
    # The Hopf normal form: the origin's equilibria (stable for mu < 0, unstable above, HB at 0)
    # in the lower panel, the family born at their Hopf point (switch_at = "origin:HB1") above.
    (tmp_path / "hopf2.toml").write_text(HOPF)
    (tmp_path / "hb.toml").write_text("""case = "hopf2.toml"
parameter = "mu"
axis = "frequency"
equilibria_axis = "y"

[[equilibria]]
name = "origin"
from = -0.5
to = 0.5

[[branches]]
name = "cycles"
from = 0.0
to = 0.5
switch_at = "origin:HB1"
""")
    result = sympathy.study(str(tmp_path / "hb.toml"), out=str(tmp_path / "out"))
    family = result.branches["cycles"]
    assert family.error == "" and np.allclose(family.points.period, np.pi, rtol=1e-6)
    for study in (result, sympathy.load(tmp_path / "out" / "hb.json")):
        ax = sympathy.plot.study(study)
        top, below = ax.figure.axes
        assert top is ax and below.get_ylabel() == "y (equilibria)"
        drawn = [(line.get_gid(), np.asarray(line.get_xdata()))
                 for line in below.get_lines() if line.get_gid() in ("stable", "unstable")]
        assert [gid for gid, _ in drawn] == ["stable", "unstable"]
        assert abs(drawn[0][1][-1]) < 1e-8 and abs(drawn[1][1][0]) < 1e-8  # changed at the HB
        assert any(str(line.get_gid()) == "event HB" for line in below.get_lines())
        assert any(line.get_gid() == "stable" for line in top.get_lines())
    with pytest.raises(ValueError, match="two panels; no ax"):
        sympathy.plot.study(result, ax=plt.subplots()[1])


def test_the_plot_script_draws_a_study_with_equilibria(tmp_path, transcritical):
    # scripts/plot_study on the program's JSON, by the same module (the build's, as here).
    source = os.environ.get("SYMPATHY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "../.."))
    _, loaded = transcritical
    out = tmp_path / "tc.svg"
    env = dict(os.environ, SYMPATHY_BUILD_DIR=os.path.dirname(os.path.dirname(
        os.path.dirname(sympathy.__file__))))
    subprocess.run([os.path.join(source, "scripts/plot_study"), loaded.path, "--out", str(out)],
                   check=True, capture_output=True, env=env)
    assert out.read_text().lstrip().startswith("<?xml")
