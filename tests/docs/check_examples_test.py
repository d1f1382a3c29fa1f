"""Tests of scripts/check_examples, the documentation's example checker: it must fail on one
changed digit, accept an output shown with fewer digits than printed, honour `...`, and
--update must rewrite only what changed and report the relative change."""

import importlib.machinery
import importlib.util
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "check_examples"


def load():
    loader = importlib.machinery.SourceFileLoader("check_examples", str(SCRIPT))
    spec = importlib.util.spec_from_loader("check_examples", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


check = load()


def run(tmp_path, text, *options):
    doc = tmp_path / "doc.md"
    doc.write_text(text)
    done = subprocess.run([sys.executable, str(SCRIPT), "--sympathy", "/bin/true", *options,
                           str(doc)], capture_output=True, text=True)
    return done.returncode, done.stdout + done.stderr, doc.read_text()


PERIOD = "```console\n$ echo 'period 0.577048204146 s'\n{}\n```\n"


@pytest.mark.parametrize("shown,ok", [
    ("period 0.577048204146 s", True),   # as printed
    ("period 0.577048204147 s", False),  # the last digit changed
    ("period 0.577048 s", True),         # fewer digits, correctly rounded
    ("period 0.577049 s", False),        # fewer digits, wrongly rounded
    ("period 0.5770 s", True),
    ("period 0.5771 s", False),
    ("period ... s", True),              # masked
    ("period 0.577048204146 ms", False),  # text changed
])
def test_one_changed_digit_fails(tmp_path, shown, ok):
    status, out, _ = run(tmp_path, PERIOD.format(shown))
    assert (status == 0) == ok, out


def test_number_rule():
    assert check.number_matches("1.5e-3", "1.46e-3")
    assert not check.number_matches("1.5e-3", "1.44e-3")
    assert check.number_matches("12", "12")
    assert not check.number_matches("12", "13")
    assert check.number_matches("+0.000000", "-0.000000")  # a zero's sign is noise
    # A hash's digits look like a number with a huge exponent: compared as text.
    assert check.number_matches("08e83107244", "08e83107244")
    assert not check.number_matches("08e83107244", "08e83107245")


def test_elided_lines(tmp_path):
    text = "```console\n$ printf 'a\\nb\\nc\\nd\\n'\na\n...\nd\n```\n"
    assert run(tmp_path, text)[0] == 0
    text = "```console\n$ printf 'a\\nb\\nc\\nd\\n'\na\n...\nc\n```\n"
    assert run(tmp_path, text)[0] == 1


def test_failing_command_fails(tmp_path):
    assert run(tmp_path, "```console\n$ false\n```\n")[0] == 1
    assert run(tmp_path, "```console\n$ false; echo \"exit $?\"\nexit 1\n```\n")[0] == 0


def test_prompt_outside_an_example_block_is_an_error(tmp_path):
    status, out, _ = run(tmp_path, "```sh\n$ echo hi\n```\n")
    assert status == 2 and "doc.md:2" in out
    assert run(tmp_path, "<!-- not run: builds everything -->\n```sh\n$ echo hi\n```\n")[0] == 0


def test_python_blocks_share_a_namespace(tmp_path):
    text = "```pycon\n>>> x = 2.5\n>>> x * 2\n5.0\n```\ntext\n```pycon\n>>> print(x)\n2.5\n```\n"
    assert run(tmp_path, text)[0] == 0
    text = "```pycon\n>>> 1 / 0\nTraceback (most recent call last):\n...\nZeroDivisionError: division by zero\n```\n"
    assert run(tmp_path, text)[0] == 0
    assert run(tmp_path, "```pycon\n>>> 1 / 0\n```\n")[0] == 1


def test_update_rewrites_only_what_changed(tmp_path):
    text = ("intro\n\n```console\n$ printf 'period 0.5770482 s\\nrun time 0.03 s\\nsame\\n'\n"
            "period 0.5770 s\nrun time ... s\nold\n```\nafter\n")
    status, out, new = run(tmp_path, text, "--update")
    assert status == 1
    assert new == ("intro\n\n```console\n$ printf 'period 0.5770482 s\\nrun time 0.03 s\\nsame\\n'\n"
                   "period 0.5770 s\nrun time ... s\nsame\n```\nafter\n")
    assert run(tmp_path, new)[0] == 0
    text = PERIOD.format("period 0.5771 s")
    status, out, new = run(tmp_path, text, "--update")
    assert "0.5771 -> 0.577048204146" in out and "relative change 8.98e-05" in out
    assert "period 0.577048204146 s" in new
    assert "largest change" in out


def test_update_masks_run_times(tmp_path):
    text = "```console\n$ echo 'run time     0.028 s'\n```\n"
    _, _, new = run(tmp_path, text, "--update")
    assert "run time     ... s" in new


def test_update_keeps_a_changed_lines_masks(tmp_path):
    text = "```console\n$ echo 'period 0.577048204146 s (step 17)'\nperiod 0.5771 s (step ...)\n```\n"
    status, out, new = run(tmp_path, text, "--update")
    assert status == 1 and "0.5771 -> 0.577048204146" in out
    assert "period 0.577048204146 s (step ...)" in new


def test_links_stay_in_the_repository(tmp_path):
    # A repository of its own: the checker, a README and a page.
    repo = tmp_path / "repo"
    (repo / "scripts").mkdir(parents=True)
    (repo / "docs").mkdir()
    (repo / "scripts" / "check_examples").write_text(SCRIPT.read_text())
    (repo / "README.md").write_text("front door\n")

    def links(text):
        page = repo / "docs" / "page.md"
        page.write_text(text)
        done = subprocess.run([sys.executable, str(repo / "scripts" / "check_examples"),
                               "--sympathy", "/bin/true", str(page)],
                              capture_output=True, text=True)
        return done.returncode, done.stdout + done.stderr

    assert links("[ok](../README.md) [web](https://doi.org/10.1063/1.4965031) [a](#top)\n")[0] == 0
    status, out = links("See [the model](../../shared/MODEL.md).\n")
    assert status == 2 and "outside the repository" in out
    status, out = links("[gone](nothere.md)\n")
    assert status == 2 and "nothere.md: no such file" in out
    assert links("```text\n[not a link](nothere.md)\n```\n")[0] == 0


def test_figures_every_png_a_page_shows_is_drawn(tmp_path):
    # A repository of its own whose scripts/figures --docs draws fig08.png alone: a page that
    # shows fig12.png too fails naming it, a PNG outside cases/figures fails (that script draws
    # none), a page generated from a notebook is the notebook's, and a failing script fails.
    repo = tmp_path / "repo"
    (repo / "scripts").mkdir(parents=True)
    (repo / "cases" / "figures").mkdir(parents=True)
    (repo / "docs" / "notebook").mkdir(parents=True)
    (repo / "scripts" / "check_examples").write_text(SCRIPT.read_text())
    for name in ("cases/figures/fig08.png", "cases/figures/fig12.png", "docs/notebook/f.png"):
        (repo / name).write_bytes(b"\x89PNG")
    figures = repo / "scripts" / "figures"

    def drawing(exit_code):
        figures.write_text(
            "import pathlib, sys\n"
            "out = pathlib.Path(sys.argv[sys.argv.index('--docs') + 1])\n"
            "out.mkdir(parents=True, exist_ok=True)\n"
            "(out / 'fig08.png').write_bytes(b'\\x89PNG')\n"
            "print(f'wrote {out}/fig08.png')\n"
            f"sys.exit({exit_code})\n")

    def check_page(text):
        page = repo / "docs" / "page.md"
        page.write_text(text)
        done = subprocess.run([sys.executable, str(repo / "scripts" / "check_examples"),
                               "--sympathy", "/bin/true", "--figures", str(tmp_path / "out"),
                               str(page)], capture_output=True, text=True)
        return done.returncode, done.stdout + done.stderr

    drawing(0)
    status, out = check_page("![a](../cases/figures/fig08.png)\n")
    assert status == 0 and "1 shown in the checked documents, all drawn" in out
    status, out = check_page("![a](../cases/figures/fig08.png)\n\n"
                             "![b](../cases/figures/fig12.png)\n")
    assert status == 1 and "docs/page.md:3: shows ../cases/figures/fig12.png, which " \
        "scripts/figures --docs did not draw" in out
    status, out = check_page("![n](notebook/f.png)\n")
    assert status == 1 and "does not draw (it draws the PNGs of cases/figures)" in out
    status, out = check_page("<!-- Generated from x.ipynb by scripts/notebook_markdown: do not "
                             "edit. -->\n\n![n](notebook/f.png)\n")
    assert status == 0 and "0 shown" in out
    drawing(3)
    status, out = check_page("![a](../cases/figures/fig08.png)\n")
    assert status == 1 and "FAILED (exit status 3)" in out
