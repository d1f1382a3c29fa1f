"""The Python package `sympathy` of the build, for the plotting scripts beside this file
(scripts/plot, plot_study, plot_map, plot_timeseries, plot_basins): its python/ folder in
SYMPATHY_BUILD_DIR (default build/ of this repository), matplotlib without a display.

    from built_package import sympathy    # sympathy.load, sympathy.plot, sympathy.Result
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")

_root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(_root, os.environ.get("SYMPATHY_BUILD_DIR", "build"), "python"))

import sympathy  # noqa: E402
import sympathy.plot  # noqa: E402,F401

__all__ = ["sympathy"]
