# Sphinx configuration of sympathy's documentation (built by scripts/docs, warnings as errors).
#
# Why Sphinx and not MkDocs: the documentation holds the C++ API, read from the headers' own
# comments by Doxygen and shown through Breathe, and the Python module's docstrings through
# autodoc; MkDocs 1.4 with mkdocstrings 0.20 has a Python handler and nothing for C++. Pages are
# Markdown all the same (MyST). Every package is Debian's (scripts/setup docs), and nothing
# reaches the network while building: no intersphinx, no remote images.
import os
import pathlib
import sys

here = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(here / "_ext"))
if os.environ.get("SYMPATHY_PYTHON_PATH"):
    sys.path.insert(0, os.environ["SYMPATHY_PYTHON_PATH"])

project = "sympathy"
author = "the sympathy developers"
copyright = "2026, the sympathy developers"

extensions = ["myst_parser", "sphinx.ext.autodoc", "sphinx.ext.mathjax", "sympathy_help"]
doxygen_xml = os.environ.get("SYMPATHY_DOXYGEN_XML")
if doxygen_xml:
    extensions.append("breathe")
    breathe_projects = {"sympathy": doxygen_xml}
    breathe_default_project = "sympathy"
    breathe_default_members = ("members",)

myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]
html_theme = "alabaster"
html_theme_options = {"description": "periodic orbits, their stability and their bifurcations",
                      "fixed_sidebar": True}
html_static_path = []
# The pages' fenced blocks are ```console and ```pycon (run by scripts/check_examples), ```toml,
# ```cpp, ```text; Pygments knows them all.
highlight_language = "text"
autodoc_member_order = "bysource"
