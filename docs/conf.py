"""Sphinx configuration of the mechopt documentation (``make docs``).

The API reference is generated from the docstrings (autodoc + numpydoc); the
tutorials and the output reference are Markdown pages (myst-parser). The build
runs with warnings as errors (``sphinx-build -W --keep-going``).
"""
from __future__ import annotations

import sys
from pathlib import Path

import mechopt  # the installed package (make docs installs it with the docs extra)

# the local extension docs/_ext/mechopt_tables.py (tables rendered from the registry)
sys.path.insert(0, str(Path(__file__).resolve().parent / "_ext"))

project = "mechopt"
author = "mechopt contributors"
copyright = "mechopt contributors, MIT license"
version = release = mechopt.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.intersphinx",
    "numpydoc",
    "myst_parser",
    "mechopt_tables",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "Thumbs.db", ".DS_Store"]
templates_path: list[str] = []

# --- autodoc -----------------------------------------------------------------
autodoc_default_options = {
    "members": True,            # the names of each module's __all__
    "member-order": "bysource",
    "show-inheritance": False,
}
autodoc_typehints = "none"      # numpydoc's sections carry the types; signatures stay short
autodoc_inherit_docstrings = True
autoclass_content = "class"

# --- intersphinx -------------------------------------------------------------
# Links to Python, numpy, pandas, matplotlib and pymoo. The build runs offline (CI has
# no network): it reads the small inventories shipped in docs/_inv/ (written by
# docs/gen_inventories.py: the names the docstrings use, each to its page). With
# MECHOPT_DOCS_ONLINE=1 it downloads each project's full objects.inv instead.
import os  # noqa: E402

_HERE = Path(__file__).resolve().parent
_ONLINE = os.environ.get("MECHOPT_DOCS_ONLINE") == "1"
_PROJECTS = {
    "python": "https://docs.python.org/3/",
    "numpy": "https://numpy.org/doc/stable/",
    "pandas": "https://pandas.pydata.org/docs/",
    "matplotlib": "https://matplotlib.org/stable/",
    "pymoo": "https://pymoo.org/",
}
intersphinx_mapping = {
    name: (url, None if _ONLINE else str(_HERE / "_inv" / f"{name}.inv"))
    for name, url in _PROJECTS.items()
}
intersphinx_timeout = 10

# --- numpydoc ----------------------------------------------------------------
numpydoc_show_class_members = False   # autodoc's :members: lists them once
numpydoc_class_members_toctree = False
# the types of Parameters/Returns entries link to Python, numpy, pandas, pymoo
# (intersphinx above); a word without an alias stays plain text
numpydoc_xref_param_type = True
numpydoc_xref_ignore = "all"
numpydoc_xref_aliases = {
    "ndarray": "numpy.ndarray",
    "Generator": "numpy.random.Generator",
    "DataFrame": "pandas.DataFrame",
    "Series": "pandas.Series",
    "Path": "pathlib.Path",
    "Figure": "matplotlib.figure.Figure",
    "Axes": "matplotlib.axes.Axes",
    "Problem": "pymoo.core.problem.Problem",
    "Result": "pymoo.core.result.Result",
    "Callback": "pymoo.core.callback.Callback",
    "Algorithm": "pymoo.core.algorithm.Algorithm",
}
numpydoc_validation_checks: set[str] = set()

# --- myst --------------------------------------------------------------------
myst_heading_anchors = 3
myst_enable_extensions: list[str] = []

# --- HTML --------------------------------------------------------------------
html_theme = "alabaster"
html_title = f"mechopt {release}"
html_static_path: list[str] = []
html_show_sourcelink = False
