"""Sphinx configuration of the mechopt documentation (``make docs``).

The API reference is generated from the docstrings (autodoc + numpydoc); the
tutorials and the output reference are Markdown pages (myst-parser). The build
runs with warnings as errors (``sphinx-build -W --keep-going``).
"""
from __future__ import annotations

import mechopt  # the installed package (make docs installs it with the docs extra)

project = "mechopt"
author = "mechopt contributors"
copyright = "mechopt contributors, MIT license"
version = release = mechopt.__version__

extensions = [
    "sphinx.ext.autodoc",
    "numpydoc",
    "myst_parser",
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
# Not enabled: links to numpy, pandas, pymoo and matplotlib need their objects.inv
# inventories, which intersphinx downloads; the docs build runs offline in CI, and no
# inventory of them is shipped in docs/ yet (add them as docs/_inv/<name>.inv and set
# intersphinx_mapping = {"numpy": ("https://numpy.org/doc/stable/", "_inv/numpy.inv"), ...}).

# --- numpydoc ----------------------------------------------------------------
numpydoc_show_class_members = False   # autodoc's :members: lists them once
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
numpydoc_validation_checks: set[str] = set()

# --- myst --------------------------------------------------------------------
myst_heading_anchors = 3
myst_enable_extensions: list[str] = []

# --- HTML --------------------------------------------------------------------
html_theme = "alabaster"
html_title = f"mechopt {release}"
html_static_path: list[str] = []
html_show_sourcelink = False
