"""The paper's Fig. 8 from Python: the row setup's in-phase and anti-phase orbits versus the
platform stiffness k, stable solid, unstable dashed, bifurcations marked (README, "From Python").

    PYTHONPATH=build/python python3 python/examples/fig08.py [OUT.png]
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import sympathy

case = sympathy.Case("cases/row2.toml", params="table2")
fig, ax = plt.subplots(figsize=(6, 3.5))
for start in ("in-phase", "anti-phase"):
    branch = case.continue_branch(start=start, param="k", from_=1, to=100)
    p = branch.points
    phase = np.abs(p.phase_differences["th2"])  # th2 - th1, rad
    print(f"{start}: {len(p.value)} points, {branch.stop}")
    for e in branch.events:
        print(f"  {e.type} at k = {e.value:.10f} +- {e.uncertainty:.1e}  {e.symmetry}")
    for stable, style in ((True, "-"), (False, "--")):
        ax.plot(p.value, np.where(p.stable == stable, phase, np.nan), style,
                color="black" if stable else "grey")
    ax.plot([e.value for e in branch.events],
            np.interp([e.value for e in branch.events], p.value, phase), "o", color="C3")
ax.set_xlabel("k (N/m)")
ax.set_ylabel("|th2 - th1| (rad)")
fig.tight_layout()
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "fig08_python.png", dpi=100)
