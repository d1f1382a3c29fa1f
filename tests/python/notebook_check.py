"""The notebook tutorial (python/examples/tutorial.ipynb) run as a reader runs it, by nbclient with
the python3 kernel from the repository's root: every code cell runs, and its text output equals
the output stored in the notebook, which the docs' page (docs/guides/notebook.md, written by
scripts/notebook_markdown) shows; the page is the one that script writes; the code cells pass
mypy against the package's stubs. About 5 s.

Usage (ctest python.notebook): notebook_check.py SOURCE_DIR   (PYTHONPATH at the built package)
"""

import os
import runpy
import subprocess
import sys
import tempfile

import nbclient
import nbformat

source = os.path.abspath(sys.argv[1])
notebook = os.path.join(source, "python/examples/tutorial.ipynb")
stored = nbformat.read(notebook, as_version=4)
run = nbformat.read(notebook, as_version=4)
os.environ["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # ipykernel's debugger's note, on stderr
nbclient.NotebookClient(run, timeout=120, kernel_name="python3",
                        resources={"metadata": {"path": source}}).execute()


def text(cell) -> str:
    return "".join(o.text for o in cell.outputs if o.output_type == "stream")


failures = []
for i, (a, b) in enumerate(zip(stored.cells, run.cells)):
    if a.cell_type != "code":
        continue
    errors = [o for o in b.outputs if o.output_type == "error"]
    if errors:
        failures.append(f"cell {i}: {errors[0].ename}: {errors[0].evalue}")
    elif text(a) != text(b):
        failures.append(f"cell {i}: output differs\n--- stored\n{text(a)}--- run\n{text(b)}")
    elif any("image/png" in o.get("data", {}) for o in a.outputs) != \
            any("image/png" in o.get("data", {}) for o in b.outputs):
        failures.append(f"cell {i}: a figure in one run and not the other")

# The docs' page is the stored notebook's.
make = runpy.run_path(os.path.join(source, "scripts/notebook_markdown"))
page, _ = make["page"](notebook, "", "notebook")
with open(os.path.join(source, "docs/guides/notebook.md")) as f:
    if f.read() != page:
        failures.append("docs/guides/notebook.md differs from the notebook: run "
                        "scripts/notebook_markdown")

# The code cells as one script, type-checked against the stubs (where mypy is installed).
try:
    import mypy  # noqa: F401
except ImportError:
    print("mypy not installed: the notebook's code is not type-checked")
else:
    with tempfile.TemporaryDirectory() as tmp:
        script = os.path.join(tmp, "tutorial.py")
        with open(script, "w") as f:
            for cell in stored.cells:
                if cell.cell_type == "code":
                    f.write(cell.source + "\n\n")
        env = dict(os.environ, MYPYPATH=os.environ.get("PYTHONPATH", ""))
        # matplotlib has no stubs in Debian 12: its calls are not checked.
        check = subprocess.run([sys.executable, "-m", "mypy", "--ignore-missing-imports",
                                "--cache-dir",
                                os.path.join(tmp, "cache"), script],
                               capture_output=True, text=True, env=env)
        if check.returncode != 0:
            failures.append("mypy on the notebook's code:\n" + check.stdout)

if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"notebook: {sum(c.cell_type == 'code' for c in run.cells)} code cells ran, outputs as "
      "stored, page current")
