"""The Python module against the program: the same case, options and numbers.

Run by ctest (python.module) with PYTHONPATH at the built module, SYMPATHY_CLI the program and
SYMPATHY_SOURCE_DIR the repository. Every expected number comes from the program run in the same
test, or from the closed form of the Hopf normal form (cases/examples/hopf.toml).
"""

import math
import json
import os
import re
import signal
import subprocess
import sys
import threading
import time
import tomllib

import numpy as np
import pytest

import sympathy

SOURCE = os.environ.get("SYMPATHY_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "../.."))
CLI = os.environ.get("SYMPATHY_CLI", os.path.join(SOURCE, "build/cases/sympathy"))
ROW2 = os.path.join(SOURCE, "cases/row2.toml")
HOPF = os.path.join(SOURCE, "cases/examples/hopf.toml")


def cli(*args):
    run = subprocess.run([CLI, *args], capture_output=True, text=True, check=True)
    return run.stdout


def events_table(stdout):
    """(type, value as printed) of each row of the program's table of bifurcations."""
    rows = []
    lines = stdout.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("bifurcations"))
    for line in lines[start + 2:]:
        fields = line.split()
        if not fields or fields[0].rstrip("?") not in ("LP", "BP", "PD", "NS", "UZ", "HB"):
            break
        rows.append((fields[0], fields[1]))
    return rows


def test_branch_equals_the_program_to_the_last_printed_digit():
    # The README's worked example of `continue` (Branches and bifurcations), quiet.
    stdout = cli("continue", ROW2, "--start", "anti-phase", "--param", "k", "--from", "1",
                 "--to", "100", "--quiet")
    expected = events_table(stdout)
    assert [t for t, _ in expected] == ["BP", "NS", "NS"]

    seen = []
    branch = sympathy.Case(ROW2).continue_branch(
        start="anti-phase", param="k", from_=1, to=100, progress=seen.append)
    # The program prints each value with %.12g (print_events): compare the same text.
    got = [(e.type + ("" if e.trusted else "?"), "%.12g" % e.value) for e in branch.events]
    assert got == expected
    assert branch.stop == "parameter bound"
    n = len(branch.points.value)
    assert f"{n} points" in stdout
    # Points as arrays, in parameter order, ending on the bound; the callback saw each one.
    assert branch.points.state0.shape == (n, len(branch.state_names))
    assert branch.points.multipliers.dtype == np.complex128
    assert branch.points.value[0] == 1 and branch.points.value[-1] == 100
    assert [p.index for p in seen] == list(branch.points.index)
    bp = branch.events[0]
    assert bp.name == "branch point" and bp.symmetry == "breaks" and bp.located
    assert 0 < bp.uncertainty < 1e-6
    assert abs(abs(bp.crossing) - 1) < 1e-6


def test_orbit_equals_the_program():
    stdout = cli("orbit", ROW2, "--params", "table2", "--start", "anti-phase")
    period = re.search(r"period\s+(\S+) s", stdout).group(1)
    orbit = sympathy.Case(ROW2, params="table2").orbit(start="anti-phase")
    assert orbit.converged
    assert "%.12g" % orbit.period == period
    assert orbit.multipliers.dtype == np.complex128
    assert orbit.kinds.count("trivial") == 1
    assert orbit.stability == "unstable" and not orbit.stable
    # The program's list of moduli, to its 12 printed decimals.
    printed = re.findall(r"^\s+(\d\.\d{12})\s+[+-]", stdout, re.M)
    assert ["%.12f" % m for m in orbit.moduli] == printed
    assert orbit.trivial_multiplier_error < 1e-8 and orbit.residual < 1e-9
    # The stiffness measured before Newton, as the program prints it ("stiffness indicator 0.57").
    indicator = re.search(r"stiffness indicator (\S+)", stdout).group(1)
    assert "%.2g" % orbit.stiffness.indicator == indicator and not orbit.stiffness.stiff


def test_events_over_a_second_parameter_without_files():
    # A user's sweep: the anti-phase branch point in k for three damping values, in memory.
    case = sympathy.Case(ROW2)
    found = {}
    for c in (0.0, 0.0185, 0.1):
        branch = case.continue_branch(start="anti-phase", param="k", from_=45, to=48,
                                      set={"c": c}, accuracy="fast")
        found[c] = [e.value for e in branch.events if e.type == "BP"]
    # One BP each; at Table II's c = 0.0185 it is the README's k = 47.0656 (fast preset: 4e-7),
    # and it hardly moves with damping (README: 47.0996 at c = 0, 46.2095 at c = 0.5).
    assert all(len(v) == 1 for v in found.values())
    assert abs(found[0.0185][0] - 47.0655622632) < 1e-5
    assert abs(found[0.0][0] - 47.0996) < 1e-3
    assert found[0.1][0] < found[0.0185][0] < found[0.0][0]


def test_interrupt_returns_the_points_so_far():
    # SIGINT from another thread once the first point is in: the engine runs without the GIL and
    # its stop check runs Python's signal handlers; the call returns what it has. The callback is
    # list.append, C code in which Python runs no handler: only the stop check can see the signal.
    seen = []

    def send():
        while not seen:
            time.sleep(0.01)
        os.kill(os.getpid(), signal.SIGINT)

    sender = threading.Thread(target=send)
    sender.start()
    branch = sympathy.Case(ROW2).continue_branch(
        start="anti-phase", param="k", from_=1, to=100, progress=seen.append)
    sender.join()
    assert branch.stop == "interrupted"
    assert 1 <= len(branch.points.value) < 65  # the whole branch has 65 points
    assert len(seen) == len(branch.points.value)


def test_keyboard_interrupt_in_the_callback_returns_the_points_so_far():
    def progress(point):
        if point.index == 3:
            raise KeyboardInterrupt

    branch = sympathy.Case(HOPF).continue_branch(param="mu", from_=0.25, to=1, progress=progress)
    assert branch.stop == "interrupted"
    assert list(branch.points.index) == [0, 1, 2, 3]


def test_simulation_interrupted_keeps_its_samples():
    case = sympathy.Case(ROW2)

    def send():
        time.sleep(0.3)
        os.kill(os.getpid(), signal.SIGINT)

    sender = threading.Thread(target=send)
    sender.start()
    run = case.simulate(start="anti-phase", t_end=1e4)  # about a minute, were it not stopped
    sender.join()
    assert run.stop == "interrupted"
    assert 1 < len(run.t) < 1e6 and run.states.shape == (len(run.t), len(run.state_names))


def test_simulation_equals_the_programs_csv_also_with_the_pendula_locked(tmp_path):
    # The same request as the program (app::prepare_simulation): its CSV's samples to the last
    # digit it writes (17 significant), for the whole model and the platform alone.
    case = sympathy.Case(ROW2)
    for locked in (False, True):
        out = tmp_path / f"run{int(locked)}.csv"
        flags = ["--locked-pendula"] if locked else []
        cli("simulate", ROW2, "--start", "anti-phase", "--t-end", "2", "--dt", "0.5",
            "--out", str(out), *flags)
        program = np.genfromtxt(out, delimiter=",", names=True)
        run = case.simulate(start="anti-phase", t_end=2, dt=0.5, locked_pendula=locked)
        assert list(program.dtype.names) == ["t", *run.state_names]
        assert np.array_equal(program["t"], run.t)
        for k, name in enumerate(run.state_names):
            assert np.array_equal(program[name], run.states[:, k]), name
    assert "th1" not in run.state_names  # the platform alone


def test_progress_true_draws_a_tqdm_bar_over_the_parameter_range(capsys):
    pytest.importorskip("tqdm")
    branch = sympathy.Case(HOPF).continue_branch(param="mu", from_=0.25, to=1, progress=True)
    assert branch.stop == "parameter bound"
    err = capsys.readouterr().err
    # The bar's last state: the whole range, 0.75 of mu, covered.
    assert "continue mu: 100%" in err and "0.75/0.75" in err


def test_an_exception_in_the_callback_is_raised_after_the_run():
    def progress(point):
        if point.index == 2:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        sympathy.Case(HOPF).continue_branch(param="mu", from_=0.25, to=1, progress=progress)


def test_import_without_numpy_says_so():
    # A Python without NumPy (None in sys.modules makes its import fail): the import itself
    # fails, naming NumPy, before any computation.
    code = "import sys; sys.modules['numpy'] = None; import sympathy"
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert run.returncode != 0
    assert "ImportError: sympathy needs NumPy" in run.stderr, run.stderr


def test_bad_options_raise_input_error_naming_the_option():
    case = sympathy.Case(ROW2)
    with pytest.raises(sympathy.InputError, match=r"^step: expected a positive number"):
        case.continue_branch(start="anti-phase", param="k", from_=1, to=100, step=-1)
    with pytest.raises(ValueError, match=r"^param q: not a parameter of .*expected one of"):
        case.continue_branch(start="anti-phase", param="q", from_=1, to=100)
    with pytest.raises(sympathy.InputError, match=r"start nowhere"):
        case.orbit(start="nowhere")
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'max_stp'"):
        case.continue_branch(start="anti-phase", param="k", from_=1, to=100, max_stp=0.1)
    with pytest.raises(sympathy.InputError, match=r"no-such-file.toml"):
        sympathy.Case(os.path.join(SOURCE, "no-such-file.toml"))


def test_equation_case_file_orbit_simulation_and_parameters():
    # The Hopf normal form: the circle r = sqrt(mu), period 2 pi / w, nontrivial multiplier
    # exp(-4 pi mu / w) (cases/examples/hopf.toml).
    case = sympathy.Case(HOPF)
    assert case.parameters == {"mu": 0.25, "w": 1.0}
    assert case.state_names == ["x", "y"]
    fast = sympathy.Case(HOPF, params="fast").with_values(mu=0.36)
    assert fast.parameters == {"mu": 0.36, "w": 2.0}
    orbit = fast.orbit()
    assert abs(orbit.period - math.pi) < 1e-8
    other = orbit.multipliers[[k != "trivial" for k in orbit.kinds]]
    assert abs(other[0] - math.exp(-4 * math.pi * 0.36 / 2)) < 1e-8
    run = case.simulate(t_end=2, dt=0.5, start="outside")
    assert list(run.t) == [0, 0.5, 1, 1.5, 2]
    assert run.states.shape == (5, 2) and run.stop == "end time"
    assert list(run.states[0]) == [1.0, 0.0]


def test_hopf_curve_of_equilibria_equals_the_program(tmp_path):
    # Lorenz's Hopf curve in (rho, sigma) from an equilibria JSON: the same object as
    # sympathy.load gives for the program's JSON, on rho_H(sigma) = sigma (sigma + beta + 3) /
    # (sigma - beta - 1) (1e-9 relative), stopped at sigma = 20 as asked.
    lrz = os.path.join(SOURCE, "cases/examples/lrz.toml")
    eq = str(tmp_path / "eq.json")
    cli("equilibria", lrz, "--param", "rho", "--from", "30", "--to", "2", "--start",
        "near-equilibrium", "--quiet", "--json", eq)
    words = dict(parent=eq, event="HB1", param="rho", from_=0, to=200, second="sigma",
                 second_from=5, second_to=30)
    curve = sympathy.Case(lrz).curve(stop_at={"sigma": 20}, **words)
    assert curve.kind == "curve" and curve.of == "equilibria" and curve.first == "rho"
    s, beta = curve.points.second, 8 / 3
    assert np.all(abs(curve.points.first - s * (s + beta + 3) / (s - beta - 1))
                  < 1e-9 * curve.points.first)
    assert [(e.type, e.second) for e in curve.events] == [("UZ", 20.0)]
    saved = str(tmp_path / "hopf.json")
    cli("curve", lrz, "--parent", eq, "--event", "HB1", "--param", "rho", "--from", "0", "--to",
        "200", "--second", "sigma", "--second-from", "5", "--second-to", "30", "--stop-at",
        "sigma=20", "--quiet", "--json", saved)
    loaded = sympathy.load(saved)
    assert list(loaded.points.first) == list(curve.points.first)
    with pytest.raises(sympathy.InputError, match=r"^event BP1: expected a fold or Hopf point"):
        sympathy.Case(lrz).curve(**dict(words, event="BP1"))


def test_switches_at_codimension_two_points(tmp_path):
    # The Bautin form's GH -> its fold of cycles on b1 = -b2^2 / 4 (1e-8), with the family it
    # started from as `branch`; the BT form's BT on its Hopf curve -> the fold curve
    # b1 = b2^2 / 4 (1e-9), the object sympathy.load gives.
    bautin = os.path.join(SOURCE, "cases/examples/bautin.toml")
    eq, hb = str(tmp_path / "eq.json"), str(tmp_path / "hb.json")
    cli("equilibria", bautin, "--param", "b1", "--from", "-0.5", "--to", "0.5", "--quiet",
        "--json", eq)
    cli("curve", bautin, "--parent", eq, "--event", "HB1", "--param", "b1", "--from", "-1",
        "--to", "1", "--second", "b2", "--second-from", "-1", "--second-to", "1", "--quiet",
        "--json", hb)
    lpc = sympathy.curve(bautin, parent=hb, event="GH1", param="b1", from_=-1, to=0.1,
                         second="b2", second_from=-1, second_to=0.5)
    a, b = lpc.points.first, lpc.points.second
    assert lpc.kind == "LP" and len(a) > 10 and np.all(abs(a + b * b / 4) < 1e-8)
    assert lpc.branch.origin == "HB at b1 = 0"
    bt = os.path.join(SOURCE, "cases/examples/bt.toml")
    cli("equilibria", bt, "--param", "b1", "--from", "0.1", "--to", "-0.1", "--quiet",
        "--json", eq)
    cli("curve", bt, "--parent", eq, "--event", "HB1", "--param", "b1", "--from", "-1",
        "--to", "1", "--second", "b2", "--second-from", "-1.5", "--second-to", "1", "--quiet",
        "--json", hb)
    fold = sympathy.curve(bt, parent=hb, event="BT1", param="b1", from_=-1, to=1, second="b2",
                          second_from=-1.5, second_to=1)
    assert fold.of == "equilibria" and fold.origin.startswith("BT at b1 = ")
    assert np.all(abs(fold.points.first - fold.points.second ** 2 / 4) < 1e-9)


def test_curve_equals_the_program():
    # A short stretch of the anti-phase BP curve in (k, c) (tests/cli/curve_test.sh's, at the
    # fast preset to keep it short): Python and the program, the same points, stop and events.
    options = ["--start", "anti-phase", "--param", "k", "--from", "46", "--to", "48",
               "--event", "BP1", "--second", "c", "--second-from", "0.0185",
               "--second-to", "0.021", "--accuracy", "fast", "--quiet"]
    stdout = cli("curve", ROW2, *options)
    seen = []
    curve = sympathy.Case(ROW2).curve(
        start="anti-phase", param="k", from_=46, to=48, event="BP1", second="c",
        second_from=0.0185, second_to=0.021, accuracy="fast", progress=seen.append)
    assert curve.kind == "BP" and curve.first_name == "k" and curve.second_name == "c"
    n = len(curve.points.first)
    assert f"  {n} points; stopped: {curve.stop_reason}\n" in stdout
    assert curve.points.second[-1] == 0.021
    assert len(seen) == n
    # Each point described by the model, as a branch's are: the orbits on the anti-phase BP
    # curve keep th2 = -th1, so both pendula swing equally (1e-9).
    amplitudes = curve.points.amplitudes
    assert len(amplitudes["th1"]) == n and min(amplitudes["th1"]) > 0.1
    assert max(abs(amplitudes["th1"] - amplitudes["th2"])) < 1e-9
    printed = re.findall(r"^  turn in k\s+(\S+)\s+(\S+)", stdout, re.M)
    assert [("%.12g" % e.first, "%.12g" % e.second) for e in curve.events] == printed
    # k falls steadily as c grows here: no turn in k (the tangent's k component, 2e-3 of it in
    # the scaled norm, used to flip sign by noise and report ten).
    assert not printed and all(b < a for a, b in zip(curve.points.first, curve.points.first[1:]))
    branch_points = int(re.search(r"^  the branch: (\d+) points", stdout, re.M).group(1))
    assert len(curve.branch.points.value) == branch_points and curve.branch.events[0].type == "BP"
    with pytest.raises(sympathy.InputError, match=r"^event NS1: the branch has no such event"):
        sympathy.Case(ROW2).curve(start="anti-phase", param="k", from_=46, to=48, event="NS1",
                                  second="c", second_from=0.0185, second_to=0.021,
                                  accuracy="fast")


SMALL_STUDY = """title = "small"
case = "{case}"
params = "table2"
parameter = "k"
axis = "phase"

[[branches]]
name = "anti-phase"
start = "anti-phase"
from = 45.0
to = 50.0

[[branches]]
name = "in-phase"
start = "in-phase"
from = 1.0
to = 100.0
"""


def test_study_equals_the_program(tmp_path):
    # A two-branch study (the worked example's, one on a short window, at the fast preset), by the
    # program and by Python: the same events on each branch to the last printed digit.
    study = tmp_path / "small.toml"
    study.write_text(SMALL_STUDY.format(case=ROW2))
    stdout = cli("study", str(study), "--out", str(tmp_path / "cli"), "--accuracy", "fast")
    result = sympathy.study(str(study), out=str(tmp_path / "py"), accuracy="fast")
    assert list(result.branches) == ["anti-phase", "in-phase"]
    for name, branch in result.branches.items():
        assert branch.error == "" and branch.stop == "parameter bound"
        table = stdout[stdout.index(f"bifurcations on {name}:"):]
        expected = events_table(table)
        got = [(e.type + ("" if e.trusted else "?"), "%.12g" % e.value) for e in branch.events]
        assert got == expected and got
        assert (tmp_path / "py" / f"small-{name}.csv").exists()
    # The study's JSON as the program writes it: equal but for the run times.
    def without_times(path):
        data = json.loads(path.read_text())
        data.pop("seconds")
        for b in data["branches"]:
            b.pop("seconds")
            b["stiffness"].pop("seconds")
        return data

    assert (without_times(tmp_path / "py" / "small.json") ==
            without_times(tmp_path / "cli" / "small.json"))


def test_study_interrupted_returns_its_branches_so_far(tmp_path):
    # The branches run on threads of their own; the calling thread watches for the signal.
    study = tmp_path / "small.toml"
    study.write_text(SMALL_STUDY.format(case=ROW2))
    sender = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    sender.start()
    result = sympathy.study(str(study), out=str(tmp_path), accuracy="fast")  # 1.2 s unstopped
    sender.join()
    assert "interrupted" in [b.stop for b in result.branches.values()]


def test_fit_equals_the_program(tmp_path):
    # README's fitting example, from Python: one metronome's angle simulated (10 s here) with noise
    # of 0.005 rad, d and s fitted from wrong starts, by the program and by Python.
    single = sympathy.Case(os.path.join(SOURCE, "cases/single.toml"))
    run = single.simulate(start="swing", t_end=10)
    th1 = run.states[:, run.state_names.index("th1")]
    noisy = th1 + np.random.default_rng(1).normal(0.0, 0.005, th1.size)
    data = tmp_path / "angle.csv"
    np.savetxt(data, np.column_stack([run.t, noisy]), delimiter=",", header="t,th1",
               comments="", fmt="%.17g")
    options = dict(data=str(data), free=["d", "s"], free_initial=["th1"],
                   set={"d": 2e-6, "s": 5.4e-5})
    stdout = cli("fit", single.path, "--data", str(data), "--free", "d,s", "--free-initial",
                 "th1", "--set", "d=2e-6", "--set", "s=5.4e-5")
    fit = single.fit(**options)
    assert fit.converged and fit.names == ["d", "s", "th1(0)"]
    printed = dict(re.findall(r"^\s+(?:fitted\s+)?(d|s|th1\(0\))\s+(\S+)\s", stdout, re.M))
    assert {n: "%.10g" % v for n, v in zip(fit.names, fit.values)} == printed
    # Against the truth (Table I: d = 2.4e-6, s = 4.51e-5), within three standard errors.
    assert abs(fit.parameters["d"] - 2.4e-6) < 3 * fit.errors[0]
    assert abs(fit.parameters["s"] - 4.51e-5) < 3 * fit.errors[1]
    assert fit.correlation.shape == (3, 3)


def test_fit_interrupted_returns_its_best_point_so_far(tmp_path):
    # A global search of 20000 evaluations (minutes) stopped by SIGINT after 0.5 s: the fit ends
    # at the best point so far, with its statistics, not converged, and says it was interrupted.
    single = sympathy.Case(os.path.join(SOURCE, "cases/single.toml"))
    run = single.simulate(start="swing", t_end=4, dt=0.05)
    data = tmp_path / "angle.csv"
    np.savetxt(data, np.column_stack([run.t, run.states[:, run.state_names.index("th1")]]),
               delimiter=",", header="t,th1", comments="", fmt="%.17g")
    sender = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    sender.start()
    started = time.monotonic()
    fit = single.fit(data=str(data), free=["d", "s"], set={"d": 2e-6, "s": 5.4e-5},
                     global_=True, global_evaluations=20000)
    sender.join()
    assert fit.interrupted and not fit.converged and fit.stop_reason == "interrupted"
    assert time.monotonic() - started < 30
    assert fit.rss <= fit.rss_start and np.all(np.isfinite(fit.values))


def test_case_from_a_dict():
    # row2.toml read into a dict is the same case; a wrong key is named by its key path.
    with open(ROW2, "rb") as f:
        contents = tomllib.load(f)
    from_dict = sympathy.Case(contents, params="table2")
    from_file = sympathy.Case(ROW2, params="table2")
    assert from_dict.parameters == from_file.parameters
    assert from_dict.orbit(start="anti-phase").period == from_file.orbit(start="anti-phase").period
    contents["metronome"]["mpp"] = contents["metronome"].pop("mp")
    with pytest.raises(sympathy.InputError) as error:
        sympathy.Case(contents)
    message = str(error.value)
    assert message.startswith("the case dict: key 'metronome.mpp': expected one of the keys")
    assert "sympathy-case-" not in message and ".toml" not in message
    with pytest.raises(sympathy.InputError, match=r"key 'metronome.mp\[0\]': expected a str"):
        sympathy.Case({"metronome": {"mp": [None]}})


def test_hopf_family_with_the_first_orbits_amplitude():
    # The family born at abc's HB1 from a first orbit of amplitude 0.005 (continue's
    # --hopf-amplitude): AUTO's two folds of cycles, p1 = 0.211903 and 0.213697 (test/hyper.all).
    abc = os.path.join(SOURCE, "cases/examples/abc.toml")
    branch = sympathy.Case(abc).continue_branch(param="p1", from_=0.2, to=0.25, switch_at="HB1",
                                                hopf_amplitude=0.005)
    assert sorted(round(e.value, 6) for e in branch.events if e.type == "LP") == [0.211903,
                                                                                 0.213697]


def test_equilibria_equal_the_program():
    # AUTO's demo abc: four Hopf points of the equilibria (cases/examples/abc.toml; its header
    # gives AUTO's values, p1 = 0.204184536, 0.229839038, 0.259957854, 0.346208522).
    abc = os.path.join(SOURCE, "cases/examples/abc.toml")
    stdout = cli("equilibria", abc, "--param", "p1", "--from", "0", "--to", "0.4", "--quiet")
    seen = []
    branch = sympathy.Case(abc).equilibria(param="p1", from_=0, to=0.4, progress=seen.append)
    assert [(e.type, "%.12g" % e.value) for e in branch.events] == events_table(stdout)
    assert [round(e.value, 9) for e in branch.events] == [0.204184536, 0.229839038, 0.259957854,
                                                         0.346208522]
    first = branch.events[0]
    assert "omega %.10g, period %.10g" % (first.omega, first.period) in stdout
    assert first.lyapunov < 0  # supercritical
    assert len(seen) == len(branch.points.value) and branch.stop == "parameter bound"
    assert branch.points.eigenvalues.shape == (len(seen), 3)


def test_signatures_list_every_keyword_with_its_type_and_default():
    # Every public function's keywords are the command's options (the one option table): real
    # signatures for inspect, help() and IDEs; None leaves an option to the command's default,
    # and a required option has no default.
    import inspect
    import pydoc
    import sympathy._core as core  # type: ignore[import]  # the extension has no stubs

    for name, (command, _, progress) in sympathy._FUNCTIONS.items():
        for function in (getattr(sympathy, name), getattr(sympathy.Case, name)):
            sig = inspect.signature(function)
            keywords = [p for p in sig.parameters.values()
                        if p.kind == inspect.Parameter.KEYWORD_ONLY]
            table = core.command_options(command)
            assert [p.name for p in keywords] == \
                [o["keyword"] for o in table] + (["progress"] if progress else [])
            for p, o in zip(keywords, table):
                assert (p.default is inspect.Parameter.empty) == o["required"], p.name
            assert o["help"] in function.__doc__
            assert name in pydoc.render_doc(function)
    sig = inspect.signature(sympathy.continue_branch)
    assert sig.parameters["from_"].default is inspect.Parameter.empty  # required
    assert sig.parameters["max_points"].default is None
    assert "``max_points`` (int)" in sympathy.continue_branch.__doc__
    assert "global_" in inspect.signature(sympathy.fit).parameters  # --global


def test_wrong_types_raise_type_error_and_bad_values_input_error_naming_the_keyword():
    case = sympathy.Case(HOPF)
    window = dict(param="mu", from_=0.25, to=0.3)
    for bad, expected in [(dict(from_="0.25"), r"from_ must be a float or an int, not str"),
                          (dict(max_points=1.5), r"max_points must be an int, not float"),
                          (dict(max_points=True), r"max_points must be an int, not bool"),
                          (dict(user_points="0.3"), r"user_points must be a sequence of floats"),
                          (dict(method=1), r"method must be a str, not int"),
                          (dict(initial=[0.1]), r"initial must be a mapping of str to float")]:
        with pytest.raises(TypeError, match=expected):
            case.continue_branch(**{**window, **bad})
    for bad, expected in [(dict(method="rk4"), r"^method rk4: expected bdf, adams or erk"),
                          (dict(max_points=0), r"^max_points"),
                          (dict(step=float("nan")), r"^step nan: expected a finite number"),
                          (dict(step=10**400), r"^step 1000.*: expected a finite number"),
                          (dict(max_points=2**40), r"^max_points 1099511627776: expected an "),
                          (dict(param="q"), r"^param q: not a parameter")]:
        with pytest.raises(sympathy.InputError, match=expected):
            case.continue_branch(**{**window, **bad})
    with pytest.raises(TypeError, match=r"missing a required argument: 'to'"):
        sympathy.continue_branch(HOPF, param="mu", from_=0.25)


def test_module_functions_take_a_path_a_dict_or_a_case_and_values_as_values():
    # sympathy.orbit(path) is Case(path).orbit(); a number reaches the engine as the float it
    # is (0.1 + 0.2 is the branch's first value to the last bit), a path object as a path.
    import pathlib
    by_path = sympathy.orbit(pathlib.Path(HOPF))
    by_case = sympathy.Case(HOPF).orbit()
    assert by_path.period == by_case.period and by_path.stability == by_case.stability
    start = 0.1 + 0.2
    branch = sympathy.continue_branch(HOPF, param="mu", from_=start, to=0.35, max_points=3)
    assert branch.points.value[0] == start


def test_type_stubs_are_the_option_tables():
    # python/sympathy/__init__.pyi is generated from the table (scripts/python_stubs); mypy
    # checks the tests against it (ctest python.types).
    import sympathy._options as options
    with open(os.path.join(SOURCE, "python/sympathy/__init__.pyi")) as f:
        assert f.read() == options.stub_text(sympathy._FUNCTIONS), \
            "the stubs differ from the option table: run scripts/python_stubs"


def timeless(j):
    """A program's JSON without its run times (which differ from run to run; nothing else may)."""
    if isinstance(j, dict):
        return {k: timeless(v) for k, v in j.items() if k != "seconds"}
    return [timeless(v) for v in j] if isinstance(j, list) else j


def test_map_equals_the_program(tmp_path):
    # A small map (the anti-phase orbit near its BP, the BP curve in c, a 3 x 2 stability grid)
    # by the program and by Python: the same curves, grid and events, to the last digit of the
    # JSON both write.
    import json
    map_file = tmp_path / "map_small.toml"
    map_file.write_text(
        f'title = "small"\ncase = "{ROW2}"\nparams = "table2"\n'
        '[first]\nparameter = "k"\nfrom = 45.0\nto = 49.0\npoints = 3\n'
        '[second]\nparameter = "c"\nfrom = 0.0185\nto = 0.03\npoints = 2\n'
        '[[orbits]]\nname = "anti-phase"\nstart = "anti-phase"\n')
    cli("map", str(map_file), "--out", str(tmp_path / "cli"), "--quiet")
    result = sympathy.map(map_file, out=tmp_path / "py", jobs=1)
    assert result.json == str(tmp_path / "py" / "map_small.json")
    program = timeless(json.load(open(tmp_path / "cli" / "map_small.json")))
    python = timeless(json.load(open(result.json)))
    assert program["orbits"] == python["orbits"]
    assert [c["kind"] for c in python["orbits"][0]["curves"]] == ["BP"]
    orbit = result.orbits[0]
    assert orbit.error == "" and orbit.curves[0].kind == "BP"
    assert orbit.grid.unstable_count == [[1, 1, 0], [1, 1, 0]]
    assert [e.type for e in orbit.branch.events] == ["BP"]
    with pytest.raises(TypeError, match=r"jobs must be an int"):
        sympathy.map(map_file, jobs="2")
    with pytest.raises(sympathy.InputError, match=r"^jobs: expected a positive integer"):
        sympathy.map(map_file, jobs=0)


def test_map_with_equilibria_equals_the_program(tmp_path):
    # The Bautin map (a cycle and the equilibrium, cases/examples/bautin_map.toml) by the program
    # and by Python: the same equilibria entry to the last digit of the JSON; its Hopf line's GH
    # at the origin (1e-8, the closed form) with l2 = -4 (1e-6: the form's r^4 term, |q| = 1).
    import json
    path = os.path.join(SOURCE, "cases/examples/bautin_map.toml")
    # Exit code 7: the fold of cycles stops short (minimum step) where it nears GH.
    run = subprocess.run([CLI, "map", path, "--out", str(tmp_path / "cli"), "--quiet",
                          "--accuracy", "fast"], capture_output=True, text=True)
    assert run.returncode == 7, run.stderr
    result = sympathy.map(path, out=tmp_path / "py", accuracy="fast")
    program = timeless(json.load(open(tmp_path / "cli" / "bautin_map.json")))
    python = timeless(json.load(open(result.json)))
    assert program["equilibria"] == python["equilibria"]
    entry = result.equilibria[0]
    assert entry.name == "origin" and [c.kind for c in entry.curves] == ["HB"]
    assert entry.branch.kind == "equilibria"
    [gh] = [e for e in entry.curves[0].events if e.type == "GH"]
    assert abs(gh.first) < 1e-8 and abs(gh.second) < 1e-8
    assert gh.coefficients["l2"] == pytest.approx(-4, rel=1e-6)
    assert [c.kind for c in result.orbits[0].curves] == ["LP"]


def test_load_gives_back_what_the_program_wrote(tmp_path):
    # AUTO's load: the JSON `continue --json`, `orbit --json`, `equilibria --json` write, read
    # back; its numbers are the ones the functions return for the same request, to the last bit.
    branch_json, orbit_json, eq_json = (str(tmp_path / f) for f in ("b.json", "o.json", "e.json"))
    cli("continue", HOPF, "--param", "mu", "--from", "0.25", "--to", "1", "--user-points", "0.5",
        "--quiet", "--json", branch_json)
    cli("orbit", HOPF, "--json", orbit_json)
    cli("equilibria", HOPF, "--param", "mu", "--from", "0", "--to", "0.5", "--quiet",
        "--json", eq_json)
    loaded = sympathy.load(branch_json)
    branch = sympathy.continue_branch(HOPF, param="mu", from_=0.25, to=1, user_points=[0.5])
    assert loaded.kind == "branch" and loaded.stop == branch.stop
    assert np.array_equal(loaded.points.value, branch.points.value)
    assert np.array_equal(loaded.points.period, branch.points.period)
    assert np.array_equal(loaded.points.multipliers, branch.points.multipliers)
    assert [(e.type, e.value) for e in loaded.events] == \
        [(e.type, e.value) for e in branch.events]
    orbit = sympathy.load(orbit_json)
    assert orbit.kind == "orbit" and orbit.period == sympathy.orbit(HOPF).period
    assert np.array_equal(orbit.multipliers, sympathy.orbit(HOPF).multipliers)
    eq = sympathy.load(eq_json)
    assert eq.kind == "equilibria"
    assert np.array_equal(eq.points.value,
                          sympathy.equilibria(HOPF, param="mu", from_=0, to=0.5).points.value)
    (tmp_path / "x.json").write_text('{"a": 1}')
    with pytest.raises(sympathy.InputError, match=r"x.json: expected a JSON the program writes"):
        sympathy.load(tmp_path / "x.json")


def test_results_as_dicts_and_tables():
    # Every result is a Result: to_dict() gives plain containers (arrays as lists), and a
    # branch's points are a table: one row a point, a 2-D field's columns as NAME[j], a dict's as
    # NAME.LABEL (to_dataframe, where pandas is installed).
    import json
    branch = sympathy.continue_branch(HOPF, param="mu", from_=0.25, to=0.5)
    assert isinstance(branch, sympathy.Result) and isinstance(branch.points, sympathy.Points)
    d = branch.to_dict()
    assert d["points"]["value"] == branch.points.value.tolist()
    assert d["events"] == [e.to_dict() for e in branch.events]
    json.dumps({k: v for k, v in d["points"].items() if k != "multipliers"})
    columns = branch.points.columns()
    n = len(branch.points.value)
    assert all(len(c) == n for c in columns.values())
    assert "state0[1]" in columns and "amplitudes.x" in columns
    try:
        import pandas  # type: ignore[import]  # noqa: F401 (optional)
    except ImportError:
        with pytest.raises(ImportError, match="to_dataframe needs pandas"):
            branch.to_dataframe()
    else:
        assert list(branch.to_dataframe()["value"]) == list(branch.points.value)
    assert isinstance(sympathy.orbit(HOPF), sympathy.Result)


def test_basins_equal_the_program(tmp_path):
    # A small basins study (2 grid points, 4 starts each, 30 s runs) by the program and by
    # Python on its threads: the same runs and shares, the same files; the result is the JSON
    # as load reads it.
    cli("basins", ROW2, "--grid", "k=45:55:2", "--starts", "4", "--t-end", "30",
        "--out", str(tmp_path / "cli"), "--quiet")
    result = sympathy.basins(ROW2, grid="k=45:55:2", starts=4, t_end=30, out=tmp_path / "py")
    assert result.kind == "basins" and not result.interrupted and result.complete
    for name in ("basins_runs.csv", "basins_shares.csv"):
        assert (tmp_path / "cli" / name).read_text() == (tmp_path / "py" / name).read_text()
    program = sympathy.load(tmp_path / "cli" / "basins.json")
    assert [p.values for p in result.points] == [p.values for p in program.points]
    assert [{s: v.count for s, v in p.shares.items()} for p in result.points] == \
        [{s: v.count for s, v in p.shares.items()} for p in program.points]
    with pytest.raises(sympathy.InputError, match=r"^grid: expected one or two parameter grids"):
        sympathy.basins(ROW2, starts=4, out=tmp_path / "none")


def test_basins_stop_early_as_the_program_does(tmp_path):
    # early_stop=True: the same files as the program's --early-stop (stopped_at, certified_by),
    # every run certified by a case's start at Table III with the class of the run that is not
    # stopped early, and each state's times to synchronize summarized.
    import csv
    args = ("--params", "table3", "--grid", "k=47.0899", "--starts", "6", "--t-end", "60")
    cli("basins", ROW2, *args, "--early-stop", "--out", str(tmp_path / "cli"), "--quiet")
    cli("basins", ROW2, *args, "--out", str(tmp_path / "full"), "--quiet")
    result = sympathy.basins(ROW2, params="table3", grid="k=47.0899", starts=6, t_end=60,
                             early_stop=True, out=tmp_path / "py")
    for name in ("basins_runs.csv", "basins_shares.csv"):
        assert (tmp_path / "cli" / name).read_text() == (tmp_path / "py" / name).read_text()
    early = list(csv.DictReader(open(tmp_path / "py" / "basins_runs.csv")))
    full = list(csv.DictReader(open(tmp_path / "full" / "basins_runs.csv")))
    assert [r["class"] for r in early] == [r["class"] for r in full]
    assert all(r["certified_by"] in ("in-phase", "anti-phase", "in-phase-low") for r in early)
    assert all(float(r["stopped_at"]) < 60 for r in early)
    for state, share in result.points[0].shares.items():
        assert share.t_sync["median"] is None or share.t_sync["q1"] <= share.t_sync["median"]


def test_equilibria_and_curve_draw_a_tqdm_bar(capsys):
    # progress=True on every function that takes it (True was called as a callback here, a
    # TypeError, before): equilibria over the parameter's range, a curve over its points.
    pytest.importorskip("tqdm")
    abc = os.path.join(SOURCE, "cases/examples/abc.toml")
    sympathy.equilibria(abc, param="p1", from_=0, to=0.4, progress=True)
    assert "equilibria p1: 100%" in capsys.readouterr().err
    curve = sympathy.curve(ROW2, start="anti-phase", param="k", from_=44, to=50, event="BP1",
                           second="c", second_from=0.0185, second_to=0.02, accuracy="fast",
                           progress=True)
    assert f"curveBP1:{len(curve.points.first)}points" in capsys.readouterr().err.replace(" ", "")


def test_jobs_report_progress_as_counts_and_as_a_tqdm_bar(tmp_path, capsys):
    # A study's branches, basins' runs: the callable hears (done, total) as jobs finish, from the
    # calling thread, ending at the total; progress=True draws a tqdm bar over the jobs.
    study = tmp_path / "small.toml"
    study.write_text(SMALL_STUDY.format(case=ROW2))
    heard = []
    sympathy.study(str(study), out=str(tmp_path), accuracy="fast",
                   progress=lambda done, total: heard.append((done, total)))
    assert heard[-1] == (2, 2) and all(t == 2 for _, t in heard)
    assert [d for d, _ in heard] == sorted(d for d, _ in heard)
    pytest.importorskip("tqdm")
    sympathy.basins(ROW2, grid="k=45:55:2", starts=2, t_end=20, out=tmp_path / "b", progress=True)
    assert "basins: 100%" in capsys.readouterr().err


def test_sweep_equals_the_program_and_the_closed_form(tmp_path):
    # The Hopf normal form's orbit at w = 1, 1.5, 2: period 2 pi / w (closed form, to 1e-9), the
    # files the same as the program's.
    cli("sweep", HOPF, "--over", "w=1:2:3", "--out", str(tmp_path / "cli"), "--quiet")
    result = sympathy.sweep(HOPF, over="w=1:2:3", out=tmp_path / "py")
    assert result.kind == "sweep" and result.complete and not result.interrupted
    for o, w in zip(result.orbits, (1.0, 1.5, 2.0)):
        assert o.value == w and abs(o.period - 2 * math.pi / w) < 1e-9
    assert (tmp_path / "cli" / "sweep_orbits.csv").read_text() == \
        (tmp_path / "py" / "sweep_orbits.csv").read_text()
    with pytest.raises(TypeError, match=r"missing a required argument: 'over'"):
        sympathy.sweep(HOPF, out=tmp_path / "none")  # type: ignore[call-arg]
    with pytest.raises(sympathy.InputError, match=r"^over w: expected NAME=FROM:TO:COUNT"):
        sympathy.sweep(HOPF, over="w", out=tmp_path / "none")


def test_hybrid_branch_ends_at_its_grazing_as_the_program_says(tmp_path):
    # The paper's escapement (eq. 2): the in-phase branch in the hinge damping d ends where the
    # swing grazes the escapement angle, the stop and its message as the program prints them.
    case = tmp_path / "row2_impulsive.toml"
    with open(ROW2) as f:
        case.write_text(f.read().replace('escapement = "half"', 'escapement = "impulsive"', 1))
    stdout = cli("continue", str(case), "--start", "in-phase", "--param", "d", "--from",
                 "2.4e-6", "--to", "1e-4", "--quiet")
    branch = sympathy.Case(str(case)).continue_branch(start="in-phase", param="d", from_=2.4e-6,
                                                      to=1e-4)
    assert branch.stop == "grazing"
    assert f"{len(branch.points.value)} points; stopped: grazing near d = 1.5679" in stdout
    assert [(e.type, "%.12g" % e.value) for e in branch.events] == events_table(stdout)
